// What a final-gather ray brings back from the photons (photon_gather.cpp gather_from_photons).
#include "steadylight/passes/photon_gather.h"

#include <gtest/gtest.h>

#include "steadylight/base/halton.h"
#include "support/bsdf_checks.h"
#include "support/scene_builder.h"

namespace steadylight {
namespace {

using testing::add_material;
using testing::add_object;
using testing::make_empty_scene;

/// 80,000 photons over a 20 m x 20 m horizontal plane at `height`, arriving from the side of
/// `normal` (up or down), with power giving it `irradiance`.
std::vector<Photon> plane_photons(float height, Vec3 normal, float irradiance) {
    constexpr int count = 80'000;
    std::vector<Photon> stored;
    for (int i = 0; i < count; ++i)
        stored.push_back({{-10 + 20 * halton(0, uint64_t(i)), height, -10 + 20 * halton(1, uint64_t(i))},
                          normal,
                          normal,
                          Rgb{1, 1, 1} * (400.0f * irradiance / count)});
    return stored;
}

/// Photons arriving from below over a 20 m x 20 m ceiling at height 1: irradiance 1.
PhotonMap ceiling_photons() {
    std::vector<Photon> stored = plane_photons(1, {0, -1, 0}, 1);
    const int count = int(stored.size());
    return PhotonMap(std::move(stored), count);
}

// A coated floor (one quad: two triangles) under a wide diffuse ceiling whose photons give it
// irradiance 1 (as estimated from them). Gather rays that meet the floor read its base (no photons there: nothing) and
// go on along the coat, kept by Russian roulette, to the ceiling, of radiance rho / pi. On average over many rays that
// is the coat's albedo times the ceiling's radiance. Rays that meet one triangle must not share the roulette's choice
// (they did: every ray went on, weighted by 1 / its chance, or none did, 3% too bright in the textured Blender room).
TEST(PhotonGather, RaysOffACoatBringTheCoatsAlbedoOfWhatItReflects) {
    SceneDesc desc = make_empty_scene({0, 0.5f, -3}, {0, 0, 0});
    const float ceiling_albedo = 0.5f;
    MaterialDesc coated{
        .type = MaterialType::pbr, .reflectance = {0.001f, 0.001f, 0.001f}, .ior = 3, .roughness = 0.3f};
    add_object(desc, make_quad({-1, 0, -1}, {0, 0, 2}, {2, 0, 0}), add_material(desc, coated));
    add_object(desc, make_quad({-10, 1, -10}, {20, 0, 0}, {0, 0, 20}),
               add_material(desc, {.reflectance = {ceiling_albedo, ceiling_albedo, ceiling_albedo}}));
    const Scene scene(std::move(desc));
    const PreparedFrame frame(scene, 0);

    const PhotonMap map = ceiling_photons();
    const IrradiancePhotons photons(map, 1, {.k = 50, .max_radius = 0.5f}, {});

    // The ceiling's radiance as gathered straight up from under it, where the coat's rays land.
    double ceiling = 0;
    for (int i = 0; i < 400; ++i) {
        const Ray up{{-2 + 4 * halton(0, uint64_t(i)), 0.5f, -2 + 4 * halton(1, uint64_t(i))}, {0, 1, 0}};
        ceiling += gather_from_photons(frame.context(), photons, 0.5f, Visibility::everything, up).L.g / 400;
    }
    // Rays of one direction from a grid of origins: every ray sees the coat from the same wo.
    const Vec3 d = normalize(Vec3{0.3f, -1, 0.1f});
    double sum = 0;
    int went_on = 0, rays = 0;
    for (int i = 0; i < 120; ++i)
        for (int j = 0; j < 120; ++j) {
            const Vec3 target{-0.95f + 1.9f * (float(i) + 0.5f) / 120, 0, -0.95f + 1.9f * (float(j) + 0.5f) / 120};
            const Ray ray{target - d * 0.5f, d};
            const GatherHit hit = gather_from_photons(frame.context(), photons, 0.5f, Visibility::everything, ray);
            EXPECT_EQ(gather_from_photons(frame.context(), photons, 0.5f, Visibility::everything, ray).L.g, hit.L.g)
                << "the same ray gets the same numbers";
            sum += hit.L.g;
            went_on += hit.L.g > 0;
            ++rays;
        }
    const auto coat = make_bsdf(scene.desc().materials[0])->non_diffuse_part();
    const double coat_albedo =
        testing::directional_albedo(*coat, testing::direction(-d.y, 0), TransportMode::radiance, 256).g;
    const double expected = coat_albedo * ceiling;
    std::printf("rays that went on along the coat: %.3f; mean radiance %.5f, expected %.5f\n", double(went_on) / rays,
                sum / rays, expected);
    EXPECT_GT(went_on, rays / 20);
    EXPECT_LT(went_on, rays * 9 / 10);
    EXPECT_NEAR(sum / rays, expected, 0.05 * expected);
}

// Light reaches a gather ray through a stack of glass panes only after many bounces: three
// smooth panes are six surfaces to cross. On average over many rays the ray brings back the
// ceiling's radiance times the stack's transmittance, (1 - R) / (1 + (2n - 1) R) for n panes of
// reflectance R = 4% at each face (incoherent multiple reflections): 0.8. Gather rays once
// followed 4 bounces and brought back nothing here; in rough glass, which holds light by total
// internal reflection for dozens of bounces, that lost 1.2% of blender_glass's light.
// The panes are smooth glass: MaterialDesc's default roughness (0.3) made them rough, and a rough
// pane transmits less at normal incidence (its microfacets turn light to grazing angles, where
// more of it is reflected back or held in the pane by total internal reflection; the BSDF itself
// conserves energy, rough_dielectric_test.cpp): 0.790 with it, 0.624 at roughness 0.6.
TEST(PhotonGather, RaysCrossAStackOfGlassPanes) {
    SceneDesc desc = make_empty_scene({0, 0.5f, -3}, {0, 0, 0});
    add_object(desc, make_quad({-10, 1, -10}, {20, 0, 0}, {0, 0, 20}),
               add_material(desc, {.reflectance = {0.5f, 0.5f, 0.5f}}));
    const int glass = add_material(desc, {.type = MaterialType::dielectric, .ior = 1.5f, .roughness = 0});
    constexpr int panes = 3;
    for (int i = 0; i < panes; ++i) add_object(desc, make_box({0, 0.3f + 0.2f * float(i), 0}, {8, 0.02f, 8}), glass);
    const Scene scene(std::move(desc));
    const PreparedFrame frame(scene, 0);

    const PhotonMap map = ceiling_photons();
    const IrradiancePhotons photons(map, 1, {.k = 50, .max_radius = 0.5f}, {});

    constexpr int rays = 16000;
    double above = 0, below = 0;
    for (int i = 0; i < rays; ++i) {
        const float x = -1 + 2 * halton(0, uint64_t(i)), z = -1 + 2 * halton(1, uint64_t(i));
        above +=
            gather_from_photons(frame.context(), photons, 0.5f, Visibility::everything, {{x, 0.9f, z}, {0, 1, 0}}).L.g /
            rays;
        below +=
            gather_from_photons(frame.context(), photons, 0.5f, Visibility::everything, {{x, 0.1f, z}, {0, 1, 0}}).L.g /
            rays;
    }
    const double R = 0.04, expected = (1 - R) / (1 + (2 * panes - 1) * R);
    std::printf("through %d panes: %.4f of the ceiling's radiance (expected %.4f)\n", panes, below / above, expected);
    EXPECT_NEAR(below / above, expected, 0.01);  // 3 standard deviations of 16,000 rays
}

// Where no record reaches, a point estimates its irradiance as much as it counts in its pixel
// (BranchShare): a full gather, a gather with a sixteenth of the rays, or, beyond glass's
// reflection, the irradiance at the nearest irradiance photon, no ray traced. All three estimate
// the same irradiance. Under a ceiling, a white floor whose photons give it irradiance 1 sends up
// radiance rho / pi, so the ceiling receives about rho (the planes, 20 m wide and 1 m apart, fill
// nearly all of its hemisphere); the ceiling's own photons say rho too.
TEST(PhotonGather, EveryBranchShareEstimatesTheSameIrradiance) {
    SceneDesc desc = make_empty_scene({0, 0.5f, -3}, {0, 0, 0});
    const float rho = 0.5f;
    const int white = add_material(desc, {.reflectance = {rho, rho, rho}});
    add_object(desc, make_quad({-10, 0, -10}, {0, 0, 20}, {20, 0, 0}), white);  // the floor, facing up
    add_object(desc, make_quad({-10, 1, -10}, {20, 0, 0}, {0, 0, 20}), white);  // the ceiling, facing down
    const Scene scene(std::move(desc));
    const PreparedFrame frame(scene, 0);
    const FrameContext& context = frame.context();

    std::vector<Photon> stored = plane_photons(0, {0, 1, 0}, 1);
    const std::vector<Photon> ceiling = plane_photons(1, {0, -1, 0}, rho);
    stored.insert(stored.end(), ceiling.begin(), ceiling.end());
    const int count = int(stored.size());
    const PhotonMap map(std::move(stored), count);
    const IrradiancePhotons photons(map, 1, {.k = 50, .max_radius = 0.5f}, {});
    const GatherSettings gather;
    const PointFallbacks fallbacks = make_point_fallbacks(context, photons, 0.5f, gather);

    const Ray up{{0.3f, 0.5f, -0.2f}, {0, 1, 0}};
    const std::optional<Hit> hit = context.tracer.intersect(up);
    ASSERT_TRUE(hit);
    const SurfacePoint sp = face_towards(make_surface_point(scene, context.frame, up, *hit), up.d);
    for (const BranchShare share : {BranchShare::whole, BranchShare::glossy, BranchShare::minor}) {
        const GatherResult result = fallbacks.at(share)(sp, sp.ns);
        const int rays = share == BranchShare::whole    ? gather.theta_strata * gather.phi_strata
                         : share == BranchShare::glossy ? gather.theta_strata * gather.phi_strata / 16
                                                        : 0;
        std::printf("share %d: E %.4f from %d rays (expected %.4f)\n", int(share), result.record.E.g, result.rays, rho);
        EXPECT_EQ(result.rays, rays) << int(share);
        EXPECT_NEAR(result.record.E.g, rho, 0.05 * rho) << int(share);
    }
}

}  // namespace
}  // namespace steadylight
