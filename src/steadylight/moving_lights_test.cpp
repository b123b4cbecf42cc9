// Lights that move (tests/scenes/moving_lamps.json: a torch carried across a room, a sun turning,
// lighting it through a window, a glowing lantern floating across, a ball rolling): every frame
// where a light has moved is its own segment, so each method renders it as the still scene with
// the lights where they are at that frame.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "steadylight/output/frame_names.h"
#include "steadylight/output/image_writer.h"
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

/// The scene file with every light's tracks cut to their last key: the lights stand still where
/// the animation leaves them (frame 2), written as `name`.json into `dir`. The lantern, an
/// emitting object, stays marked dynamic, as its moving self is.
std::string write_lights_still_at_the_end(const fs::path& dir, const std::string& name) {
    nlohmann::json scene = nlohmann::json::parse(std::ifstream(moving_lamps));
    scene["name"] = name;
    for (nlohmann::json& light : scene["lights"]) hold_last_keys(light["animation"]);
    for (nlohmann::json& object : scene["objects"])
        if (object.contains("emission")) {
            hold_last_keys(object["animation"]);
            object["dynamic"] = true;
        }
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

    /// Frames `frames` of `scene_file` rendered by `method` into a folder of their own; the
    /// beauty of each, as float EXRs hold it.
    std::vector<Image> render(const std::string& scene_file, Method method, const std::string& frames) const {
        RenderSettings settings;
        settings.scene_file = scene_file;
        settings.out_dir =
            (m_dir / fmt::format("{}_{}", fs::path(scene_file).stem().string(), method_info(method).name)).string();
        settings.method = method;
        settings.frames = parse_frame_selection(frames);
        settings.show_progress = false;
        settings.output.exr_type = ExrPixelType::float32;
        settings.photon.photons = {.global_photons = 20'000, .caustic_photons = 0};
        settings.photon.shading.samples_per_pixel = 2;
        settings.path.samples_per_pixel = 4;
        const RenderSummary summary = render_animation(settings);
        std::vector<Image> images;
        const std::string name = Scene(load_scene_desc(scene_file)).name();
        for (const int frame : summary.frames_written)
            images.push_back(read_exr(frame_file_name(settings.out_dir, name, frame, "exr")));
        return images;
    }

    fs::path m_dir;
};

TEST_F(MovingLights, EveryFrameWhereALightMovedIsItsOwnSegment) {
    const Scene scene(load_scene_desc(moving_lamps));
    EXPECT_TRUE(scene.desc().point_lights.at(0).is_moving());
    EXPECT_TRUE(scene.desc().suns.at(0).is_moving());
    ASSERT_EQ(scene.segments().size(), 3u);
    const Scene still(load_scene_desc(write_lights_still_at_the_end(m_dir, "still")));
    EXPECT_FALSE(still.desc().point_lights.at(0).is_moving());
    EXPECT_FALSE(still.desc().suns.at(0).is_moving());
    EXPECT_EQ(still.segments().size(), 3u);  // an emitting dynamic object: every frame its own
    EXPECT_EQ(still.evaluate(0).point_lights, scene.evaluate(2).point_lights);
    EXPECT_EQ(still.evaluate(0).sun_directions, scene.evaluate(2).sun_directions);
    // The lantern, an emitting object that moves, is a light that moves too.
    const int lantern = int(scene.objects().size()) - 1;
    EXPECT_TRUE(scene.object(lantern).is_emitter());
    EXPECT_TRUE(scene.object(lantern).is_dynamic());
    EXPECT_EQ(still.evaluate(0).world_from_object[size_t(lantern)],
              scene.evaluate(2).world_from_object[size_t(lantern)]);
}

// Right first: a frame rendered as part of the moving animation is the frame of the still scene
// whose lights stand where they are then, bit for bit, in every method; and the lights did move.
TEST_F(MovingLights, AFrameIsTheStillSceneWithTheLightsWhereTheyAreThen) {
    const std::string still = write_lights_still_at_the_end(m_dir, "still");
    for (const MethodInfo& info : methods()) {
        SCOPED_TRACE(info.name);
        const std::vector<Image> moving = render(moving_lamps, info.method, "0-2");
        const std::vector<Image> standing = render(still, info.method, "2");
        ASSERT_EQ(moving.size(), 3u);
        ASSERT_EQ(standing.size(), 1u);
        EXPECT_TRUE(moving[2].pixels == standing[0].pixels);
        EXPECT_FALSE(moving[0].pixels == moving[2].pixels);
        EXPECT_FALSE(moving[0].pixels == moving[1].pixels);
    }
}

}  // namespace
}  // namespace steadylight
