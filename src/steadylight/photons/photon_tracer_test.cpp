#include "steadylight/photons/photon_tracer.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "support/scene_builder.h"

namespace steadylight {
namespace {

using testing::add_material;
using testing::add_object;
using testing::make_empty_scene;

/// Traces photons in `scene` at frame 0 with the given settings.
TracedPhotons trace(const Scene& scene, const PhotonSettings& settings) {
    return trace_photons(PreparedFrame(scene, 0).context(), settings);
}

/// A closed diffuse sphere of albedo a whose inside emits Le: the furnace of path_tracer_test.
Scene furnace(float albedo, float Le) {
    SceneDesc desc = make_empty_scene({0, 0, 0}, {0, 0, -1});
    add_object(desc, Sphere{{0, 0, 0}, 1}, add_material(desc, {.reflectance = {albedo, albedo, albedo}}), {Le, Le, Le});
    desc.objects[0].two_sided_emission = true;
    return Scene(std::move(desc));
}

Rgb total_power(const PhotonMap& map) {
    Rgb sum;
    for (const Photon& photon : map.photons()) sum += photon.power;
    return sum;
}

// Every photon hit in a closed furnace is stored, bounce after bounce: the stored power sums
// to the emitted power Phi = pi A Le (each side... here both sides emit, but photons leaving
// outwards hit nothing) times 1 + a + a^2 + ... = 1 / (1 - a). Russian roulette keeps the
// expectation: this checks that power is conserved.
TEST(PhotonTracer, FurnaceStoresEmittedPowerOverOneMinusAlbedo) {
    const float albedo = 0.6f, Le = 1.0f;
    const TracedPhotons photons =
        trace(furnace(albedo, Le), {.global_photons = 100'000, .caustic_photons = 0, .max_bounces = 64});
    // Half the photons leave the two-sided sphere outwards and are lost.
    const float inward_power = pi * 4 * pi * Le;
    const float expected = inward_power / (1 - albedo);
    EXPECT_NEAR(total_power(photons.global).r, expected, 0.01f * expected);
}

TEST(PhotonTracer, FurnaceIrradianceEstimateIsPiTimesRadiance) {
    const float albedo = 0.5f, Le = 0.5f;
    const TracedPhotons photons =
        trace(furnace(albedo, Le), {.global_photons = 200'000, .caustic_photons = 0, .max_bounces = 64});
    // Radiance Le / (1 - a) = 1 in every direction, so irradiance pi everywhere.
    const Vec3 p{0, -1, 0}, n{0, 1, 0};
    // About 32k photons per unit area: k = 2000 keeps the estimate's noise near 2%.
    const Rgb E = photons.global.estimate_irradiance(p, n, {.k = 2000, .max_radius = 0.5f});
    EXPECT_NEAR(E.g, pi, 0.05f * pi);
}

TEST(PhotonTracer, DiffuseSceneHasNoCausticPhotons) {
    const TracedPhotons photons = trace(furnace(0.5f, 1), {.global_photons = 1000, .caustic_photons = 1000});
    EXPECT_GT(photons.global.size(), 0u);
    EXPECT_EQ(photons.caustic.size(), 0u);
}

TEST(PhotonTracer, GlassSphereFocusesCausticPhotonsBelowIt) {
    // A small light above a glass sphere above a floor: caustic photons gather under the sphere.
    SceneDesc desc = make_empty_scene({0, 3, 3}, {0, 0, 0});
    const int white = add_material(desc, {});
    add_object(desc, make_quad({-5, 0, -5}, {0, 0, 10}, {10, 0, 0}), white);
    add_object(desc, Sphere{{0, 1, 0}, 0.5f}, add_material(desc, {.type = MaterialType::dielectric, .roughness = 0}));
    add_object(desc, make_quad({-0.1f, 4, -0.1f}, {0.2f, 0, 0}, {0, 0, 0.2f}), white, {100, 100, 100});
    const TracedPhotons photons = trace(Scene(std::move(desc)), {.global_photons = 0, .caustic_photons = 100'000});
    ASSERT_GT(photons.caustic.size(), 1000u);
    const DensitySettings density{.k = 50, .max_radius = 1};
    const float under = photons.caustic.estimate_irradiance({0, 0, 0}, {0, 1, 0}, density).r;
    const float beside = photons.caustic.estimate_irradiance({2, 0, 0}, {0, 1, 0}, density).r;
    EXPECT_GT(under, 20 * std::max(beside, 1e-6f));
}

TEST(PhotonTracer, SamePhotonsForOneAndTwoThreads) {
    const Scene scene(load_scene_desc(std::string(STEADYLIGHT_SOURCE_DIR) + "/scenes/table.json"));
    const PhotonSettings settings{.global_photons = 20'000, .caustic_photons = 20'000};
    TracedPhotons one, two;
    tbb::task_arena(1).execute([&] { one = trace(scene, settings); });
    tbb::task_arena(2).execute([&] { two = trace(scene, settings); });
    ASSERT_EQ(one.global.size(), two.global.size());
    ASSERT_EQ(one.caustic.size(), two.caustic.size());
    for (size_t i = 0; i < one.global.size(); ++i) ASSERT_EQ(one.global.photons()[i].p, two.global.photons()[i].p);
    for (size_t i = 0; i < one.caustic.size(); ++i)
        ASSERT_EQ(one.caustic.photons()[i].power, two.caustic.photons()[i].power);
}

}  // namespace
}  // namespace steadylight
