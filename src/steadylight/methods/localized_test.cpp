// The localized method (the frame pass, localized and frozen) and its segment pass and cache
// file: against photon mapping, bit-identical static regions, threads, light switched on.
#include "steadylight/passes/frame_pass.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <filesystem>

#include "steadylight/base/error.h"
#include "steadylight/methods/photon_mapping.h"
#include "steadylight/passes/influence.h"
#include "support/scene_builder.h"

namespace steadylight {
namespace {

using testing::add_material;
using testing::add_object;
using testing::make_empty_scene;
using testing::two_rooms_one_moving_ball;

const std::string source_dir = STEADYLIGHT_SOURCE_DIR;

PhotonMappingSettings small_settings() {
    PhotonMappingSettings settings;
    settings.photons = {.global_photons = 60'000, .caustic_photons = 0};
    settings.shading.samples_per_pixel = 4;
    return settings;
}

/// The segment pass of the whole animation, then `frames` rendered with it.
std::vector<LocalizedFrame> render(const Scene& scene, const std::vector<int>& frames,
                                   StaticCacheUse use = StaticCacheUse::corrected,
                                   const LocalizedSettings& localized = {}) {
    const PhotonMappingSettings settings = small_settings();
    RayTracer tracer(scene, scene.evaluate(0));
    const StaticSolution solution{run_segment_pass(scene, tracer, {0, scene.frame_count() - 1}, settings)};
    const Bsdfs bsdfs = make_bsdfs(scene);
    std::vector<LocalizedFrame> out;
    for (const int frame : frames) {
        const PlacedFrame placed(scene, tracer, bsdfs, frame);
        out.push_back(run_frame_pass(placed.context(), solution, settings, localized, use));
    }
    return out;
}

Scene load(const std::string& name, int width, int height) {
    Scene scene(load_scene_desc(source_dir + "/scenes/" + name + ".json"));
    scene.set_resolution(width, height);
    return scene;
}

/// A closed lit room with a sphere moving outside it, where no light reaches.
Scene room_with_hidden_ball() {
    SceneDesc desc = make_empty_scene({0, 2, -1.5f}, {0, 1.5f, 0}, 32, 24);
    desc.frame_count = 3;
    const int white = add_material(desc, {.reflectance = {0.7f, 0.7f, 0.7f}});
    add_object(desc, make_box({0, 2, 0}, {4, 4, 4}), white);
    add_object(desc, make_quad({-0.25f, 3.95f, -0.25f}, {0.5f, 0, 0}, {0, 0, 0.5f}), white, {50, 50, 50});
    add_object(desc, Sphere{{0, 0, 0}, 0.5f}, white);
    desc.objects.back().placement[0].translation_track =
        Track<Vec3>{Interpolation::linear, {0, 1}, {{10, 1, 0}, {12, 1, 0}}};
    return Scene(std::move(desc));
}

TEST(Localized, HiddenDynamicObjectGivesTheSameImageEveryFrame) {
    const std::vector<LocalizedFrame> frames = render(room_with_hidden_ball(), {0, 1, 2});
    for (const LocalizedFrame& frame : frames) {
        EXPECT_EQ(frame.stats.dynamic_photons_stored, 0);
        EXPECT_EQ(frame.stats.irradiance_records, 0);  // no L_y anywhere
        EXPECT_TRUE(frame.beauty.pixels == frames[0].beauty.pixels) << "frame " << frame.stats.frame;
    }
}

TEST(Localized, AgreesWithPhotonMappingOnBall) {
    const Scene scene = load("ball", 80, 60);
    const LocalizedFrame localized = render(scene, {15})[0];
    const PhotonFrame photon = render_photon_mapped(PreparedFrame(scene, 15).context(), small_settings());
    double sum2 = 0, sum = 0, sum_ref = 0;
    for (size_t i = 0; i < photon.beauty.pixels.size(); ++i) {
        const double y = std::min(1.0f, luminance(localized.beauty.pixels[i]));
        const double y_ref = std::min(1.0f, luminance(photon.beauty.pixels[i]));
        sum2 += (y - y_ref) * (y - y_ref), sum += y, sum_ref += y_ref;
    }
    const double n = double(photon.beauty.pixels.size()), mean_ref = sum_ref / n;
    // Both share shading noise; they differ by the indirect light only. Measured: ~1% RMSE.
    EXPECT_LT(std::sqrt(sum2 / n) / mean_ref, 0.03);
    EXPECT_LT(std::abs(sum - sum_ref) / n / mean_ref, 0.01);
    EXPECT_LT(localized.stats.irradiance_records * 3, photon.stats.irradiance_records);
}

TEST(Localized, StaticRegionsAreBitIdenticalBetweenFrames) {
    const std::vector<LocalizedFrame> frames = render(Scene(two_rooms_one_moving_ball()), {0, 1});
    const Image& a = frames[0].beauty;
    const Image& b = frames[1].beauty;
    // The room without the ball (the left half of the image: the camera's right is -x) is
    // untouched by it, to the last bit; the room with it changes.
    int changed_in_left_room = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (x < a.width / 2 - 1) {
                EXPECT_EQ(a.at(x, y), b.at(x, y)) << "pixel " << x << "," << y;
            }
            if (x > a.width / 2 + 1) changed_in_left_room += !(a.at(x, y) == b.at(x, y));
        }
    EXPECT_GT(changed_in_left_room, 20);
}

/// A long lit room (x from -3 to 3) whose camera looks at its left end while a ball rolls
/// across its right end, 4 frames: the ball is in the light's paths, and 3 m or more from what
/// the camera sees.
Scene long_room_with_far_ball() {
    SceneDesc desc = make_empty_scene({-1.2f, 1.5f, 0}, {-3, 1.2f, 0}, 32, 24, 60);
    desc.frame_count = 4;
    const int white = add_material(desc, {.reflectance = {0.7f, 0.7f, 0.7f}});
    add_object(desc, make_box({0, 1.5f, 0}, {6, 3, 3}), white);
    add_object(desc, make_quad({-0.5f, 2.99f, -0.5f}, {1, 0, 0}, {0, 0, 1}), white, {20, 20, 20});
    add_object(desc, Sphere{{0, 0, 0}, 0.3f}, white);
    desc.objects.back().placement[0].translation_track =
        Track<Vec3>{Interpolation::linear, {0, 1}, {{2.2f, 0.3f, -1}, {2.2f, 0.3f, 1}}};
    return Scene(std::move(desc));
}

/// The mean relative change of the indirect layer from each frame to the next.
double mean_indirect_change(const std::vector<LocalizedFrame>& frames) {
    double change = 0, sum = 0;
    for (size_t f = 1; f < frames.size(); ++f)
        for (size_t i = 0; i < frames[f].indirect.pixels.size(); ++i) {
            change += std::abs(luminance(frames[f].indirect.pixels[i]) - luminance(frames[f - 1].indirect.pixels[i]));
            sum += luminance(frames[f].indirect.pixels[i]);
        }
    return change / sum;
}

// Far from a moving object its true effect on the indirect light is tiny and smooth, but the
// dynamic photons there (tails of paths that met the object) land elsewhere in every frame.
// The correction takes them as the noise they are (record_correction.h): the indirect light the
// camera sees hardly moves (measured: 0.013% a frame). With every detail kept (the finest
// kernel alone) it moves by 0.6% a frame.
TEST(Localized, IndirectLightFarFromTheMovingObjectStaysStill) {
    const Scene scene = long_room_with_far_ball();
    const std::vector<LocalizedFrame> frames = render(scene, {0, 1, 2, 3});
    for (const LocalizedFrame& frame : frames) EXPECT_GT(frame.stats.dynamic_photons_stored, 1000);
    const double steady = mean_indirect_change(frames);
    LocalizedSettings every_detail;
    every_detail.correction.noise_sigmas = every_detail.correction.signal_sigmas = 0;
    const double noisy = mean_indirect_change(render(scene, {0, 1, 2, 3}, StaticCacheUse::corrected, every_detail));
    std::printf("mean indirect change a frame: %.6f (every detail kept: %.6f)\n", steady, noisy);
    EXPECT_LT(steady, 2e-4);
    EXPECT_GT(noisy, 3 * steady);
}

TEST(Localized, SameFramesOnOneOrTwoThreads) {
    const Scene scene = load("ball", 48, 36);
    std::vector<LocalizedFrame> one, two;
    tbb::task_arena(1).execute([&] { one = render(scene, {20}); });
    tbb::task_arena(2).execute([&] { two = render(scene, {20}); });
    EXPECT_TRUE(one[0].beauty.pixels == two[0].beauty.pixels);
    EXPECT_TRUE(one[0].influence.pixels == two[0].influence.pixels);
    EXPECT_EQ(one[0].stats.irradiance_records, two[0].stats.irradiance_records);
}

// The influence is estimated at every n-th pixel centre, each estimate a function of its pixel
// alone: a coarser step samples the same values at the pixels both steps share, so a large image
// may take fewer samples of the same smooth estimate.
TEST(Localized, CoarserInfluenceStepSamplesTheSameValues) {
    const Scene scene = load("ball", 64, 48);
    LocalizedSettings fine, coarse;
    fine.influence_step = 4, coarse.influence_step = 8;
    const GreyImage a = render(scene, {15}, StaticCacheUse::corrected, fine)[0].influence;
    const GreyImage b = render(scene, {15}, StaticCacheUse::corrected, coarse)[0].influence;
    int felt = 0;
    for (int y = 0; y < a.height; y += 8)
        for (int x = 0; x < a.width; x += 8) {
            EXPECT_EQ(a.at(x, y), b.at(x, y)) << "pixel " << x << "," << y;
            felt += a.at(x, y) > 0;
        }
    EXPECT_GT(felt, 5);
    EXPECT_FALSE(a.pixels == b.pixels);  // between the shared pixels, the blocks differ
}

TEST(Localized, InfluenceStepGrowsWithTheImageHeight) {
    const LocalizedSettings chosen;  // influence_step 0: by the height
    for (const auto& [height, step] : {std::pair{24, 4}, {240, 4}, {480, 4}, {959, 4}, {960, 8}, {1080, 8}, {2160, 16}})
        EXPECT_EQ(influence_step(chosen, height), step) << height << " rows";
    LocalizedSettings fixed;
    fixed.influence_step = 6;
    EXPECT_EQ(influence_step(fixed, 2160), 6);
    fixed.influence_step = -1;
    EXPECT_THROW(validate(fixed, "/localized"), InputError);
}

TEST(Localized, FrozenCacheRecomputesOnlyOnDynamicObjects) {
    const Scene scene = load("ball", 64, 48);
    const LocalizedFrame frozen = render(scene, {30}, StaticCacheUse::frozen)[0];
    const LocalizedFrame localized = render(scene, {30}, StaticCacheUse::corrected)[0];
    EXPECT_GT(frozen.stats.irradiance_records, 0);
    EXPECT_LE(frozen.stats.irradiance_records, localized.stats.irradiance_records);
}

/// tests/scenes/light_switch.json: a static room whose ceiling lamp is off for frames 0-9 and on
/// for 10-19, and a spot lamp whose intensity doubles at frame 10: two segments.
SceneDesc light_switch_desc() { return load_scene_desc(source_dir + "/tests/scenes/light_switch.json"); }

TEST(Localized, StaticCacheHashDiffersWhereTheLightIsSwitchedOn) {
    const Scene switched(light_switch_desc());
    const PhotonMappingSettings settings = small_settings();
    ASSERT_EQ(switched.segments().size(), 2u);
    const uint64_t off = static_inputs_hash(switched, switched.segments()[0], settings);
    const uint64_t on = static_inputs_hash(switched, switched.segments()[1], settings);
    EXPECT_NE(off, on);
    // Only the lights tell the segments apart: with the lights fixed as they are from frame 10
    // and the same split, both segments hash alike, and like the switched scene's second one.
    SceneDesc fixed = light_switch_desc();
    fixed.objects[1].emission_track.reset();
    fixed.objects[1].emission = {17, 12, 4};
    fixed.point_lights[0].intensity_track.reset();
    fixed.point_lights[0].intensity = {6, 6, 6};
    fixed.segment_starts = {10};
    const Scene steady(std::move(fixed));
    ASSERT_EQ(steady.segments().size(), 2u);
    EXPECT_EQ(static_inputs_hash(steady, steady.segments()[0], settings), on);
    EXPECT_EQ(static_inputs_hash(steady, steady.segments()[1], settings), on);
}

TEST(Localized, CacheFileOfTheLightOffIsNotLoadedWithTheLightOn) {
    const std::string file =
        (std::filesystem::temp_directory_path() / "steadylight_light_switch_test.irrcache").string();
    std::filesystem::remove(file);
    const Scene scene(light_switch_desc());
    const PhotonMappingSettings settings = small_settings();
    RayTracer tracer(scene, scene.evaluate(0));
    EXPECT_FALSE(load_or_run_segment_pass(scene, tracer, scene.segments()[0], settings, file).loaded);
    const StaticSolution on = load_or_run_segment_pass(scene, tracer, scene.segments()[1], settings, file);
    EXPECT_FALSE(on.loaded);
    EXPECT_NE(on.file_note.find("stale"), std::string::npos) << on.file_note;
    std::filesystem::remove(file);
}

/// With the spot lamp removed the ceiling lamp is the only light: the first segment's static
/// pass finds no light and its frames are black; the second segment's are lit.
TEST(Localized, SwitchedOnLightGivesADarkThenALitSegment) {
    SceneDesc desc = light_switch_desc();
    desc.point_lights.clear();
    const Scene scene(std::move(desc));
    const PhotonMappingSettings settings = small_settings();
    RayTracer tracer(scene, scene.evaluate(0));
    const Bsdfs bsdfs = make_bsdfs(scene);
    std::vector<LocalizedFrame> frames;
    for (const Segment& segment : scene.segments()) {
        const StaticSolution solution{run_segment_pass(scene, tracer, segment, settings)};
        const PlacedFrame placed(scene, tracer, bsdfs, segment.last);
        frames.push_back(
            run_frame_pass(placed.context(), solution, settings, LocalizedSettings{}, StaticCacheUse::corrected));
    }
    ASSERT_EQ(frames.size(), 2u);
    for (const Rgb& pixel : frames[0].beauty.pixels) EXPECT_EQ(pixel, Rgb{});
    float direct = 0, indirect = 0;
    for (size_t i = 0; i < frames[1].beauty.pixels.size(); ++i) {
        direct += frames[1].direct.pixels[i].r;
        indirect += frames[1].indirect_static.pixels[i].r;
    }
    const float n = float(frames[1].beauty.pixels.size());
    std::printf("lit segment: mean direct %.4f, mean static indirect %.4f\n", direct / n, indirect / n);
    EXPECT_GT(direct / n, 0.05f);
    EXPECT_GT(indirect / n, 0.03f);
}

TEST(Localized, StaticCacheIsSavedThenLoadedAndGoesStaleWhenTheSceneChanges) {
    const std::string file = (std::filesystem::temp_directory_path() / "steadylight_localized_test.irrcache").string();
    std::filesystem::remove(file);
    const Scene scene = load("ball", 32, 24);
    const PhotonMappingSettings settings = small_settings();
    RayTracer tracer(scene, scene.evaluate(0));
    const StaticSolution computed = load_or_run_segment_pass(scene, tracer, {0, 59}, settings, file);
    EXPECT_FALSE(computed.loaded);
    const StaticSolution loaded = load_or_run_segment_pass(scene, tracer, {0, 59}, settings, file);
    ASSERT_TRUE(loaded.loaded);
    ASSERT_EQ(loaded.cache.records().size(), computed.cache.records().size());
    for (size_t i = 0; i < loaded.cache.records().size(); ++i)
        EXPECT_EQ(loaded.cache.records()[i].E, computed.cache.records()[i].E);

    SceneDesc changed = load_scene_desc(source_dir + "/scenes/ball.json");
    for (MaterialDesc& material : changed.materials)
        if (material.name == "white") material.reflectance = {0.5f, 0.5f, 0.5f};
    Scene other(std::move(changed));
    other.set_resolution(32, 24);
    RayTracer other_tracer(other, other.evaluate(0));
    const StaticSolution stale = load_or_run_segment_pass(other, other_tracer, {0, 59}, settings, file);
    EXPECT_FALSE(stale.loaded);
    EXPECT_NE(stale.file_note.find("stale"), std::string::npos) << stale.file_note;
    std::filesystem::remove(file);
}

}  // namespace
}  // namespace steadylight
