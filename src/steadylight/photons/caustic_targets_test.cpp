#include "steadylight/photons/caustic_targets.h"

#include <gtest/gtest.h>

#include "steadylight/base/rng.h"
#include "steadylight/photons/photon_tracer.h"
#include "support/chi_square.h"
#include "support/scene_builder.h"

namespace steadylight {
namespace {

using testing::add_material;
using testing::add_object;
using testing::direction;
using testing::make_empty_scene;

/// A point lamp of intensity `intensity` 1 above a small mirror at y = 0 ([-0.5, 0.5] in x
/// and z), two glass balls beside it, under a white ceiling at y = 2.
Scene lamp_over_mirror(float intensity) {
    SceneDesc desc = make_empty_scene({0, 1, 4}, {0, 1, 0});
    const int white = add_material(desc, {.reflectance = {0.5f, 0.5f, 0.5f}});
    add_object(desc, make_quad({-0.5f, 0, -0.5f}, {0, 0, 1}, {1, 0, 0}),
               add_material(desc, {.type = MaterialType::mirror, .reflectance = {1, 1, 1}}));
    add_object(desc, make_quad({-10, 2, -10}, {20, 0, 0}, {0, 0, 20}), white);
    const int glass = add_material(desc, {.type = MaterialType::dielectric, .roughness = 0});  // smooth
    add_object(desc, Sphere{{1.5f, 0.3f, 0}, 0.3f}, glass);
    add_object(desc, Sphere{{1.7f, 0.3f, 0.2f}, 0.3f}, glass);  // its cone overlaps the first's
    desc.point_lights.push_back(
        {.name = "lamp", .position = {0, 1, 0}, .intensity = {intensity, intensity, intensity}});
    return Scene(std::move(desc));
}

/// Midpoint rule over the sphere in (cos theta, phi), fine enough for cones of a few tenths of a
/// radian.
template <class F>
double integrate_over_sphere(F&& f) {
    constexpr int n_cos = 4000, n_phi = 400;
    double sum = 0;
    for (int i = 0; i < n_cos; ++i)
        for (int j = 0; j < n_phi; ++j) sum += f(direction(-1 + (i + 0.5f) * 2 / n_cos, (j + 0.5f) * 2 * pi / n_phi));
    return sum * (2.0 / n_cos) * (2 * pi / n_phi);
}

TEST(CausticTargets, PdfIntegratesToOneOverTheSphere) {
    const Scene scene = lamp_over_mirror(1);
    const PreparedFrame frame(scene, 0);
    const CausticTargets targets(frame.context(), Visibility::everything);
    const Vec3 p{0, 1, 0};
    EXPECT_NEAR(integrate_over_sphere([&](Vec3 d) { return targets.pdf(p, d); }), 1.0, 0.01);
}

// E[1 / pdf] over sampled directions is the solid angle the cones cover together: overlapping
// cones must not be counted twice, which the pdf's count of holding cones ensures.
TEST(CausticTargets, SamplesMatchTheirPdfWhereConesOverlap) {
    const Scene scene = lamp_over_mirror(1);
    const PreparedFrame frame(scene, 0);
    const CausticTargets targets(frame.context(), Visibility::everything);
    const Vec3 p{0, 1, 0};
    const double covered = integrate_over_sphere([&](Vec3 d) { return targets.pdf(p, d) > 0 ? 1.0f : 0.0f; });
    Pcg32 rng(7);
    double sum = 0;
    constexpr int n = 200'000;
    for (int i = 0; i < n; ++i) {
        const std::optional<AimedDirection> aim = targets.sample(p, rng.next_vec2());
        ASSERT_TRUE(aim);
        EXPECT_FLOAT_EQ(aim->pdf, targets.pdf(p, aim->d));
        sum += 1 / aim->pdf;
    }
    EXPECT_NEAR(sum / n, covered, 0.01 * covered);
}

TEST(CausticTargets, InsideATargetTheLightEmitsOnItsOwn) {
    const Scene scene = lamp_over_mirror(1);
    const PreparedFrame frame(scene, 0);
    const CausticTargets targets(frame.context(), Visibility::everything);
    EXPECT_FALSE(targets.sample({1.5f, 0.3f, 0}, {0.5f, 0.5f}));
    EXPECT_EQ(targets.pdf({1.5f, 0.3f, 0}, {0, 1, 0}), 0.0f);
}

// The mirror shows the ceiling the lamp's image at y = -1: right above the mirror's centre the
// reflected irradiance is I / 3^2. Aimed photons must give that, as emission everywhere would.
TEST(CausticTargets, AimedCausticPhotonsGiveTheMirrorImagesIrradiance) {
    const float intensity = 90;
    const Scene scene = lamp_over_mirror(intensity);
    const TracedPhotons photons =
        trace_photons(PreparedFrame(scene, 0).context(), {.global_photons = 0, .caustic_photons = 200'000});
    // Nearly every photon goes into a target's cone; the mirror's reflect onto the ceiling.
    ASSERT_GT(photons.caustic.size(), 50'000u);
    const Rgb E = photons.caustic.estimate_irradiance({0, 2, 0}, {0, -1, 0}, {.k = 2000, .max_radius = 0.5f});
    EXPECT_NEAR(E.g, intensity / 9, 0.03f * intensity / 9);
}

}  // namespace
}  // namespace steadylight
