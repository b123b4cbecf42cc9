// Lights that move (tests/scenes/moving_lamps.json: a torch carried across a room, a sun turning,
// lighting it through a window, a glowing lantern floating across, a ball rolling) are lit apart
// from the static pass: their photons are traced every frame, and all of them are change
// (docs/localized.md, "Lights that move"). A frame is the still scene with its lights where they
// are then: bit for bit where the same photons light both, else within the photons' noise.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "steadylight/output/frame_names.h"
#include "steadylight/output/image_writer.h"
#include "steadylight/quality/image_error.h"
#include "steadylight/render.h"
#include "steadylight/scene/scene.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

const std::string moving_lamps = std::string(STEADYLIGHT_SOURCE_DIR) + "/tests/scenes/moving_lamps.json";

/// `animation`'s tracks cut to their last key: what they hold from then on.
void hold_last_keys(nlohmann::json& animation) {
    for (auto& [path, track] : animation.items()) {
        track["times"] = {0};
        track["values"] = {track["values"].back()};
    }
}

/// What of moving_lamps.json stands still where the animation leaves it (frame 2).
struct Still {
    bool lamps = false;          // the torch and the sun
    bool lantern = false;        // the emitting object (kept marked dynamic, as its moving self is)
    bool lantern_grows = false;  // instead, the lantern doubles in size as it moves
};

/// moving_lamps.json with `still` standing still, written as `name`.json into `dir`.
std::string write_scene(const fs::path& dir, const std::string& name, Still still) {
    nlohmann::json scene = nlohmann::json::parse(std::ifstream(moving_lamps));
    scene["name"] = name;
    if (still.lamps)
        for (nlohmann::json& light : scene["lights"]) hold_last_keys(light["animation"]);
    if (still.lantern)
        for (nlohmann::json& object : scene["objects"])
            if (object.contains("emission")) {
                hold_last_keys(object["animation"]);
                object["dynamic"] = true;
            }
    if (still.lantern_grows)
        for (nlohmann::json& object : scene["objects"])
            if (object.contains("emission"))
                object["animation"]["scale"] = {{"times", {0, 2}}, {"values", {{1, 1, 1}, {2, 2, 2}}}};
    const fs::path file = dir / (name + ".json");
    std::ofstream(file) << scene.dump(1);
    return file.string();
}

class MovingLights : public ::testing::Test {
protected:
    void SetUp() override {
        m_dir =
            fs::temp_directory_path() /
            fmt::format("steadylight_{}_{}", ::testing::UnitTest::GetInstance()->current_test_info()->name(), getpid());
        fs::remove_all(m_dir);
        fs::create_directories(m_dir);
    }
    void TearDown() override { fs::remove_all(m_dir); }

    /// Frames `frames` of `scene_file` rendered by `method` at `size` into a folder of their own;
    /// the beauty of each, as float EXRs hold it.
    std::vector<Image> render(const std::string& scene_file, Method method, const std::string& frames, int size = 32,
                              long photons = 20'000) const {
        RenderSettings settings;
        settings.scene_file = scene_file;
        settings.out_dir =
            (m_dir / fmt::format("{}_{}", fs::path(scene_file).stem().string(), method_info(method).name)).string();
        settings.method = method;
        settings.frames = parse_frame_selection(frames);
        settings.width = size, settings.height = size * 3 / 4;
        settings.show_progress = false;
        settings.output.exr_type = ExrPixelType::float32;
        settings.photon.photons = {.global_photons = photons, .caustic_photons = 0};
        settings.photon.shading.samples_per_pixel = 2;
        settings.path.samples_per_pixel = 4;
        const RenderSummary summary = render_animation(settings);
        std::vector<Image> images;
        const std::string name = Scene(load_scene_desc(scene_file)).name();
        for (const int frame : summary.frames_written)
            images.push_back(read_exr(frame_file_name(settings.out_dir, name, frame, "exr")));
        return images;
    }

    /// Frames 0-2 of `moving` and frame 2 of `still`, rendered by `method`: frame 2 is the still
    /// scene's bit for bit, and frame 0 differs (the lights did move).
    void expect_last_frame_is_the_still_scenes(const std::string& moving, const std::string& still,
                                               Method method) const {
        SCOPED_TRACE(method_info(method).name);
        const std::vector<Image> frames = render(moving, method, "0-2");
        const std::vector<Image> standing = render(still, method, "2");
        ASSERT_EQ(frames.size(), 3u);
        ASSERT_EQ(standing.size(), 1u);
        EXPECT_TRUE(frames[2].pixels == standing[0].pixels);
        EXPECT_FALSE(frames[0].pixels == frames[2].pixels);
    }

    fs::path m_dir;
};

TEST_F(MovingLights, LightsThatMoveKeepTheSegmentUnlessAnEmitterChangesSize) {
    const Scene scene(load_scene_desc(moving_lamps));
    EXPECT_TRUE(scene.desc().point_lights.at(0).is_moving());
    EXPECT_TRUE(scene.desc().suns.at(0).is_moving());
    const int lantern = int(scene.objects().size()) - 1;
    EXPECT_TRUE(scene.object(lantern).is_moving_light());
    EXPECT_EQ(scene.segments().size(), 1u);
    // An emitter that grows changes its power every frame: every frame is its own segment.
    const Scene grows(load_scene_desc(write_scene(m_dir, "lantern_grows", {.lantern_grows = true})));
    EXPECT_FALSE(grows.object(lantern).is_moving_light());
    EXPECT_EQ(grows.segments().size(), 3u);
    const Scene all_still(load_scene_desc(write_scene(m_dir, "all_still", {.lamps = true, .lantern = true})));
    EXPECT_FALSE(all_still.desc().point_lights.at(0).is_moving());
    EXPECT_FALSE(all_still.desc().suns.at(0).is_moving());
    EXPECT_EQ(all_still.evaluate(0).point_lights, scene.evaluate(2).point_lights);
    EXPECT_EQ(all_still.evaluate(0).sun_directions, scene.evaluate(2).sun_directions);
    EXPECT_EQ(all_still.evaluate(0).world_from_object[size_t(lantern)],
              scene.evaluate(2).world_from_object[size_t(lantern)]);
}

// The path tracer places every light at the frame: bit for bit the still scene, and the lights did move.
TEST_F(MovingLights, PathTracedFrameIsTheStillSceneBitForBit) {
    expect_last_frame_is_the_still_scenes(
        moving_lamps, write_scene(m_dir, "all_still", {.lamps = true, .lantern = true}), Method::path);
}

// An emitting object that moves is lit apart as the lamps are: with the lamps still, each photon
// method's frame is bit for bit the scene whose lantern stands there (marked dynamic, so that it
// is lit apart too).
TEST_F(MovingLights, EmitterThatMovesGivesTheStillEmittersFrameBitForBit) {
    const std::string lantern_moves = write_scene(m_dir, "lantern_moves", {.lamps = true});
    const std::string all_still = write_scene(m_dir, "all_still", {.lamps = true, .lantern = true});
    for (const Method method : {Method::localized, Method::photon, Method::frozen})
        expect_last_frame_is_the_still_scenes(lantern_moves, all_still, method);
}

// Lamps and suns that move are lit by photons of their own, traced every frame: the localized and
// photon frames agree with the still scene's photon frame within the photons' noise (measured at
// 64x48 with 100,000 photons: localized 1.8% per pixel, 1.2% on blocks, mean 1.001; photon 1.7%,
// 1.1%, 1.002), where frame 0, lit from where the lights start, is 68% off on blocks.
TEST_F(MovingLights, MovingLampsFrameAgreesWithTheStillScene) {
    const std::string only_lamps_move = write_scene(m_dir, "only_lamps", {.lantern = true});
    const std::string all_still = write_scene(m_dir, "all_still", {.lamps = true, .lantern = true});
    const Image reference = render(all_still, Method::photon, "2", 64, 100'000).at(0);
    for (const Method method : {Method::localized, Method::photon}) {
        SCOPED_TRACE(method_info(method).name);
        const std::vector<Image> frames = render(only_lamps_move, method, "0-2", 64, 100'000);
        ASSERT_EQ(frames.size(), 3u);
        const ImageError e = image_error(frames[2], reference);
        std::printf("%s: per pixel %.4f, blocks %.4f, mean %.4f; frame 0: blocks %.4f\n",
                    std::string(method_info(method).name).c_str(), e.pixel_rmse, e.block_rmse, e.mean_ratio,
                    image_error(frames[0], reference).block_rmse);
        EXPECT_LT(e.block_rmse, 0.05);
        EXPECT_NEAR(e.mean_ratio, 1, 0.02);
        EXPECT_GT(image_error(frames[0], reference).block_rmse, 0.15);
    }
}

}  // namespace
}  // namespace steadylight
