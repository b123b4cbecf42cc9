// Lights from far away: a sun gives its irradiance to a surface facing it, whether exactly
// parallel or spread over a cone, and a ray into its cone sees radiance that integrates to that
// irradiance; the world gives ∫ L cos dω = π L whatever its sampling; pdfs agree with samples;
// photons carry the light that crosses the disc covering the scene and start outside it.
#include <gtest/gtest.h>

#include <cmath>

#include "steadylight/base/rng.h"
#include "steadylight/base/sampling.h"
#include "steadylight/scene/shapes.h"
#include "steadylight/shading/light.h"

namespace steadylight {
namespace {

/// A 4 x 4 floor at y = 0 (the scene's bounds), lit by `suns` and `world`.
struct DistantLit {
    DistantLit(std::vector<SunLightDesc> suns, std::optional<WorldDesc> world) : scene(describe(suns, world)) {}

    static SceneDesc describe(std::vector<SunLightDesc> suns, std::optional<WorldDesc> world) {
        SceneDesc desc;
        desc.materials.push_back(MaterialDesc{});
        desc.camera.placement = {AnimatedTrs{}};
        ObjectDesc floor;
        floor.name = "floor";
        floor.geometry = make_quad({-2, 0, -2}, {0, 0, 4}, {4, 0, 0});
        floor.placement = {AnimatedTrs{}};
        desc.objects.push_back(floor);
        desc.suns = std::move(suns);
        desc.world = world;
        return desc;
    }

    Scene scene;
    FrameState frame = scene.evaluate(0);
    LightSet lights{scene, frame};
};

const Vec3 sun_travel = normalize(Vec3{1, -2, 0.5f});

SunLightDesc sun(float angle_deg) {
    return {.name = "sun", .direction = sun_travel, .irradiance = {3, 2, 1}, .angle_deg = angle_deg};
}

/// Irradiance at the origin on a surface of normal `n` from next-event samples, luminance.
double irradiance(const LightSet& lights, Vec3 n, int samples, bool with_normal) {
    Pcg32 rng(3);
    double sum = 0;
    for (int i = 0; i < samples; ++i) {
        const std::optional<LightSample> s =
            lights.sample({0, 0, 0}, rng.next_float(), rng.next_vec2(), with_normal ? n : Vec3{});
        if (!s) continue;
        EXPECT_TRUE(std::isinf(s->distance));
        sum += luminance(s->Li) * std::max(0.0f, dot(s->wi, n)) / s->pdf;
    }
    return sum / samples;
}

TEST(DistantLights, ASunGivesItsIrradianceToASurfaceFacingIt) {
    for (const float angle : {0.0f, 0.53f, 10.0f}) {
        const DistantLit lit({sun(angle)}, std::nullopt);
        const double E = irradiance(lit.lights, -sun_travel, 20000, true);
        EXPECT_NEAR(E, luminance({3, 2, 1}), 0.01 * luminance({3, 2, 1})) << angle << " degrees";
        // Tilted by 60 degrees: a cosine of a half.
        const Vec3 tilted =
            OrthonormalBasis::from_normal(-sun_travel).to_world({std::sin(pi / 3), 0, std::cos(pi / 3)});
        EXPECT_NEAR(irradiance(lit.lights, tilted, 20000, true), 0.5 * luminance({3, 2, 1}),
                    0.01 * luminance({3, 2, 1}))
            << angle << " degrees";
    }
}

TEST(DistantLights, ARayIntoTheSunsConeSeesRadianceThatAddsUpToItsIrradiance) {
    const DistantLit lit({sun(4.0f)}, std::nullopt);
    // ∫ L(w) cos dω over the sphere, with uniform directions in a cone a little wider than the sun's.
    const float cos_wide = std::cos(3.0f * pi / 180);
    const OrthonormalBasis basis = OrthonormalBasis::from_normal(-sun_travel);
    Pcg32 rng(5);
    double sum = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        const Vec3 local = sample_uniform_cone(rng.next_vec2(), cos_wide);
        sum += luminance(lit.lights.escaped_radiance(basis.to_world(local))) * local.z / uniform_cone_pdf(cos_wide);
    }
    EXPECT_NEAR(sum / n, luminance({3, 2, 1}), 0.01 * luminance({3, 2, 1}));
    EXPECT_TRUE(is_black(lit.lights.escaped_radiance(sun_travel)));  // away from the sun: nothing
    // Exactly parallel light cannot be seen, only sampled.
    const DistantLit hard({sun(0)}, std::nullopt);
    EXPECT_TRUE(is_black(hard.lights.escaped_radiance(-sun_travel)));
}

TEST(DistantLights, TheWorldGivesPiTimesItsRadianceWithOrWithoutANormal) {
    const DistantLit lit({}, WorldDesc{.color = {0.5f, 1, 2}, .strength = 2});
    const double expected = pi * luminance({1, 2, 4});
    for (const Vec3 n : {Vec3{0, 1, 0}, normalize(Vec3{1, 1, 1})})
        for (const bool with_normal : {true, false})
            EXPECT_NEAR(irradiance(lit.lights, n, 200000, with_normal), expected, 0.01 * expected) << with_normal;
    EXPECT_EQ(luminance(lit.lights.escaped_radiance(normalize(Vec3{0.3f, -1, 0.2f}))), luminance({1, 2, 4}));
}

TEST(DistantLights, SampledDirectionsAreWeighedAsEscapedRaysAre) {
    // Light sampling and a BSDF-sampled ray that escapes weigh each light by the same pdfs: a
    // direction with a BSDF pdf equal to its light pdf gets half of the light's radiance.
    const Vec3 n = normalize(Vec3{0.2f, 1, -0.1f});
    for (const bool world : {false, true}) {
        const DistantLit lit(world ? std::vector<SunLightDesc>{} : std::vector{sun(2.0f)},
                             world ? std::optional(WorldDesc{.color = {1, 1, 1}}) : std::nullopt);
        Pcg32 rng(8);
        for (int i = 0; i < 200; ++i) {
            const std::optional<LightSample> s = lit.lights.sample({0, 0, 0}, rng.next_float(), rng.next_vec2(), n);
            ASSERT_TRUE(s);
            EXPECT_NEAR(luminance(lit.lights.escaped_radiance(s->wi, n, s->pdf)), 0.5f * luminance(s->Li),
                        1e-3f * luminance(s->Li));
        }
    }
}

TEST(DistantLights, PhotonsCarryTheLightThatCrossesTheDiscCoveringTheScene) {
    const DistantLit lit({sun(0.53f)}, std::nullopt);
    const BoundingSphere& bounds = lit.scene.bounds();
    ASSERT_NEAR(bounds.radius, std::sqrt(8.0f), 1e-4f);
    Pcg32 rng(4);
    double power = 0;
    const int n = 5000;
    for (int i = 0; i < n; ++i) {
        const std::optional<EmissionSample> e =
            lit.lights.sample_emission(rng.next_float(), rng.next_vec2(), rng.next_vec2());
        ASSERT_TRUE(e);
        power += luminance(e->power);
        // From outside the scene's sphere, towards it, passing within its radius of the centre.
        EXPECT_GT(length(e->p - bounds.center), bounds.radius);
        EXPECT_LT(dot(e->d, sun_travel), 1.0001f);
        EXPECT_GT(dot(e->d, sun_travel), std::cos(0.53f * pi / 360) - 1e-5f);
        const Vec3 to_centre = bounds.center - e->p;
        EXPECT_LE(length(to_centre - e->d * dot(to_centre, e->d)), bounds.radius * 1.001f);
    }
    EXPECT_NEAR(power / n, luminance({3, 2, 1}) * pi * bounds.radius * bounds.radius, 1e-3 * power / n);
}

}  // namespace
}  // namespace steadylight
