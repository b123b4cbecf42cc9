// Photon maps composed from the static paths against maps traced whole: photon for photon, bit
// for bit, and look-ups through the composed index against an index built over the whole map.
#include "steadylight/photons/photon_paths.h"

#include <gtest/gtest.h>

namespace steadylight {
namespace {

constexpr PhotonSettings settings{.global_photons = 60'000, .caustic_photons = 60'000};

Scene load(const std::string& name) {
    return Scene(load_scene_desc(std::string(STEADYLIGHT_SOURCE_DIR) + "/scenes/" + name + ".json"));
}

void expect_same_photons(const PhotonMap& composed, const PhotonMap& traced, const std::string& what) {
    ASSERT_EQ(composed.size(), traced.size()) << what;
    EXPECT_EQ(composed.emitted(), traced.emitted()) << what;
    for (size_t i = 0; i < traced.size(); ++i) {
        const Photon &a = composed.photons()[i], &b = traced.photons()[i];
        ASSERT_TRUE(same_bits(a, b)) << what << " photon " << i << ": " << to_string(a.p) << " vs " << to_string(b.p);
    }
}

void expect_same_maps(const ComposedPhotons& composed, const TracedPhotons& traced, const std::string& what) {
    expect_same_photons(composed.maps.global, traced.global, what + " global");
    expect_same_photons(composed.maps.caustic, traced.caustic, what + " caustic");
    expect_same_photons(composed.maps.dynamic, traced.dynamic, what + " dynamic");
}

/// The k nearest of the composed map and of the traced one at points near the photons (some
/// exactly at a photon, to make ties), for the k of gathers, estimates and the influence.
void expect_same_neighbours(const PhotonMap& composed, const PhotonMap& traced, const std::string& what) {
    std::vector<Neighbour> a, b;
    const size_t step = std::max<size_t>(1, traced.size() / 400);
    for (size_t i = 0; i < traced.size(); i += step) {
        const Vec3 at = traced.photons()[i].p + Vec3{0.01f, -0.02f, 0.015f} * float(i % 3);
        for (const int k : {1, 8, 64, 300}) {
            composed.k_nearest(at, k, 0.5f, a);
            traced.k_nearest(at, k, 0.5f, b);
            ASSERT_EQ(a.size(), b.size()) << what << " at photon " << i << ", k " << k;
            for (size_t j = 0; j < a.size(); ++j)
                ASSERT_TRUE(a[j].index == b[j].index && a[j].distance2 == b[j].distance2)
                    << what << " at photon " << i << ", k " << k << ", neighbour " << j;
        }
    }
}

struct SceneFrames {
    std::string scene;
    std::vector<int> frames;
};

void PrintTo(const SceneFrames& scene_frames, std::ostream* out) { *out << scene_frames.scene; }

class ComposedMapsOnScene : public ::testing::TestWithParam<SceneFrames> {};

// Frames composed out of order, each from the static paths alone: a path a dynamic object met
// in one frame and misses in the next comes back whole.
TEST_P(ComposedMapsOnScene, EqualTracedMapsBitForBit) {
    const Scene scene = load(GetParam().scene);
    const StaticPhotonPaths paths = trace_static_photon_paths(PreparedFrame(scene, 0).context(), settings);
    for (const int frame : GetParam().frames) {
        const PreparedFrame placed(scene, frame);
        const ComposedPhotons composed = compose_photons(placed.context(), paths);
        const TracedPhotons traced = trace_photons(placed.context(), settings);
        const std::string what = GetParam().scene + " frame " + std::to_string(frame);
        expect_same_maps(composed, traced, what);
        EXPECT_GT(composed.retraced_paths, 0) << what;
        EXPECT_LT(composed.retraced_paths, (paths.global.count + paths.caustic.count) / 4) << what;
        EXPECT_GT(traced.dynamic.size(), 0u) << what;
    }
}

TEST_P(ComposedMapsOnScene, LookUpsEqualAnIndexBuiltOverTheWholeMap) {
    const Scene scene = load(GetParam().scene);
    const StaticPhotonPaths paths = trace_static_photon_paths(PreparedFrame(scene, 0).context(), settings);
    const int frame = GetParam().frames.back();
    const PreparedFrame placed(scene, frame);
    const ComposedPhotons composed = compose_photons(placed.context(), paths);
    const std::string what = GetParam().scene + " frame " + std::to_string(frame);
    for (const auto& [map, name] : {std::pair{&composed.maps.global, "global"}, {&composed.maps.caustic, "caustic"}}) {
        EXPECT_LT(map->indexed_here(), map->size() / 4 + 1) << what << " " << name;
        expect_same_neighbours(*map, PhotonMap(map->photons(), map->emitted()), what + " " + name);
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, ComposedMapsOnScene,
                         ::testing::Values(SceneFrames{"ball", {30, 0, 31, 59}}, SceneFrames{"table", {45, 12, 13}},
                                           SceneFrames{"torch_corridor", {15, 0, 29}}),
                         [](const auto& param_info) { return param_info.param.scene; });

// A sun that turns is the daylit room's only light: the static paths hold no photon, and every
// frame traces all of its photons, which are all change (the dynamic map), as full tracing does.
TEST(ComposedMaps, OnlyAMovingLightGivesEmptyStaticPathsAndTracedMaps) {
    const Scene scene = load("daylit_sweep");
    const StaticPhotonPaths paths = trace_static_photon_paths(PreparedFrame(scene, 0).context(), settings);
    EXPECT_EQ(paths.global.count, 0);
    EXPECT_EQ(paths.global.photons.size(), 0u);
    const PreparedFrame placed(scene, 20);
    const ComposedPhotons composed = compose_photons(placed.context(), paths);
    const TracedPhotons traced = trace_photons(placed.context(), settings);
    expect_same_maps(composed, traced, "daylit_sweep frame 20");
    EXPECT_EQ(composed.maps.global.emitted(), settings.global_photons);
    EXPECT_GT(traced.dynamic.size(), traced.global.size() / 3);  // every photon after its first bounce
}

// The static pass's cache may start from the paths' global map: it is the static map.
TEST(ComposedMaps, StaticPathsHoldTheStaticMap) {
    const Scene scene = load("table");
    const PreparedFrame frame(scene, 0);
    const StaticPhotonPaths paths = trace_static_photon_paths(frame.context(), settings);
    const TracedPhotons traced = trace_photons(frame.context(), settings, Visibility::static_only);
    EXPECT_TRUE(same_photons(paths.global.photons, traced.global));
    EXPECT_TRUE(same_photons(paths.caustic.photons, traced.caustic));
    EXPECT_EQ(paths.global.first_photon.back(), traced.global.size());
}

// A moving glass ball is a caustic target: caustic photons leave the lights in other directions
// each frame, so that map is traced whole; the global map is still composed.
TEST(ComposedMaps, MovingCausticTargetTracesTheCausticMapWhole) {
    const Scene scene = load("glass_move");
    const PhotonSettings small{.global_photons = 20'000, .caustic_photons = 20'000};
    const StaticPhotonPaths paths = trace_static_photon_paths(PreparedFrame(scene, 0).context(), small);
    const PreparedFrame placed(scene, 10);
    const ComposedPhotons composed = compose_photons(placed.context(), paths);
    EXPECT_TRUE(composed.caustic_traced);
    expect_same_maps(composed, trace_photons(placed.context(), small), "glass_move frame 10");
}

// The same with absorbing glass (KHR_materials_volume): blender_glass's amber ball slides over
// frames 0-12, and the paths retraced through it lose what traced ones lose. (A ball inside
// static absorbing glass: dynamic_photons_test.cpp.)
TEST(ComposedMaps, MovingAbsorbingGlassGivesTheTracedMaps) {
    const Scene scene = load("blender_glass");
    const PhotonSettings small{.global_photons = 20'000, .caustic_photons = 20'000};
    const StaticPhotonPaths paths = trace_static_photon_paths(PreparedFrame(scene, 0).context(), small);
    for (const int frame : {12, 6}) {
        const PreparedFrame placed(scene, frame);
        const ComposedPhotons composed = compose_photons(placed.context(), paths);
        const std::string what = "blender_glass frame " + std::to_string(frame);
        EXPECT_TRUE(composed.caustic_traced) << what;
        EXPECT_GT(composed.retraced_paths, 0) << what;
        expect_same_maps(composed, trace_photons(placed.context(), small), what);
    }
}

}  // namespace
}  // namespace steadylight
