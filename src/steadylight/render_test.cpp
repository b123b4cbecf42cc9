// render_animation() across runs: resume, --overwrite, other settings, and Ctrl-C.
#include "steadylight/render.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include <fmt/format.h>

#include "steadylight/base/checkpoint.h"
#include "steadylight/base/error.h"
#include "steadylight/output/frame_names.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

/// Tiny path-traced renders of BALL frames 0-1 into a folder of their own.
class RenderResume : public ::testing::Test {
protected:
    void SetUp() override {
        m_settings.scene_file = std::string(STEADYLIGHT_SOURCE_DIR) + "/scenes/ball.json";
        // One folder per test and process: ctest runs tests in parallel, maybe from several checkouts.
        m_settings.out_dir = (fs::temp_directory_path() /
                              fmt::format("steadylight_render_{}_{}",
                                          ::testing::UnitTest::GetInstance()->current_test_info()->name(), getpid()))
                                 .string();
        fs::remove_all(m_settings.out_dir);
        m_settings.method = Method::path;
        m_settings.path.samples_per_pixel = 1;
        m_settings.width = 16, m_settings.height = 12;
        m_settings.frames = parse_frame_selection("0-1");
        m_settings.show_progress = false;
    }
    void TearDown() override { fs::remove_all(m_settings.out_dir); }

    RenderSettings m_settings;
};

TEST_F(RenderResume, CompleteFramesAreSkippedUnlessOverwrite) {
    EXPECT_EQ(render_animation(m_settings).frames_written, (std::vector<int>{0, 1}));
    const RenderSummary again = render_animation(m_settings);
    EXPECT_TRUE(again.frames_written.empty());
    EXPECT_EQ(again.frames_skipped, 2);
    m_settings.overwrite = true;
    EXPECT_EQ(render_animation(m_settings).frames_written, (std::vector<int>{0, 1}));
}

TEST_F(RenderResume, TruncatedFrameIsRenderedAgain) {
    render_animation(m_settings);
    const std::string png = frame_file_name(m_settings.out_dir, "ball", 1, "png");
    fs::resize_file(png, fs::file_size(png) - 1);
    const RenderSummary again = render_animation(m_settings);
    EXPECT_EQ(again.frames_written, std::vector<int>{1});
    EXPECT_EQ(again.frames_skipped, 1);
}

TEST_F(RenderResume, OtherSettingsAreRefused) {
    render_animation(m_settings);
    m_settings.path.max_depth = 3;
    EXPECT_THROW(render_animation(m_settings), InputError);
    m_settings.overwrite = true;
    EXPECT_EQ(render_animation(m_settings).frames_written.size(), 2u);
}

TEST_F(RenderResume, InterruptDropsTheFrameInProgress) {
    request_interrupt();
    const RenderSummary stopped = render_animation(m_settings);
    clear_interrupt();
    EXPECT_TRUE(stopped.interrupted);
    EXPECT_TRUE(stopped.frames_written.empty());
    EXPECT_EQ(stopped.frames_left, (std::vector<int>{0, 1}));
    EXPECT_FALSE(fs::exists(frame_file_name(m_settings.out_dir, "ball", 0, "exr")));
    EXPECT_EQ(render_animation(m_settings).frames_written, (std::vector<int>{0, 1}));
}

TEST(Info, NamesAnimatedLightsAndTheSegmentsTheyMake) {
    const std::string text = describe_scene(std::string(STEADYLIGHT_SOURCE_DIR) + "/tests/scenes/light_switch.json");
    EXPECT_NE(text.find("2 segment(s): 0-9, 10-19"), std::string::npos) << text;
    EXPECT_NE(text.find("emitter, animated emission"), std::string::npos) << text;
    EXPECT_NE(text.find("lights: 1 area, 1 point/spot, 0 sun, 2 animated"), std::string::npos) << text;
    EXPECT_NE(text.find("spot, animated intensity"), std::string::npos) << text;
}

}  // namespace
}  // namespace steadylight
