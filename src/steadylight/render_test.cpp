// render_animation() across runs: resume, --overwrite, a dead claim left beside a complete frame,
// other settings, and Ctrl-C; a transparent background and the chosen layers in the written files.
#include "steadylight/render.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <fmt/format.h>

#include "steadylight/base/checkpoint.h"
#include "steadylight/base/error.h"
#include "steadylight/output/frame_names.h"
#include "steadylight/output/image_writer.h"
#include "steadylight/run/frame_claim.h"
#include "steadylight/run/settings_file.h"
#include "steadylight/scene/image_decoding.h"
#include "support/input_error.h"
#include "support/lock_files.h"

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

// A process killed between claiming a frame and finding it complete leaves its claim beside the
// complete frame: the next run removes it once its holder is dead, and leaves a live one alone.
TEST_F(RenderResume, DeadClaimBesideACompleteFrameIsRemoved) {
    render_animation(m_settings);
    const std::string dead = frame_claim_name(m_settings.out_dir, "ball", 0),
                      live = frame_claim_name(m_settings.out_dir, "ball", 1);
    testing::write_lock_file(dead, "elsewhere", 4242, 300);
    testing::write_lock_file(live, "elsewhere", 4243, 5);
    const RenderSummary again = render_animation(m_settings);
    EXPECT_EQ(again.frames_skipped, 2);
    EXPECT_FALSE(fs::exists(dead));
    EXPECT_TRUE(fs::exists(live));
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

/// The bytes of the file at `path`.
std::vector<unsigned char> file_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// --transparent-background end to end: alpha in the EXR (A and beauty.A) and the PNG (RGBA), the
// world left out where alpha is 0, and the option kept in the settings file like the others.
TEST_F(RenderResume, TransparentBackgroundWritesAlphaAndIsASetting) {
    fs::create_directories(m_settings.out_dir);
    m_settings.scene_file = m_settings.out_dir + "/world_ball.json";
    std::ofstream(m_settings.scene_file) << R"({"name": "world_ball",
        "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov_y": 40},
        "materials": {"grey": {"type": "lambert", "reflectance": [0.5, 0.5, 0.5]}},
        "objects": [{"name": "ball", "shape": {"type": "sphere", "radius": 0.8}, "material": "grey"}],
        "world": {"color": [0.2, 0.3, 0.5]}})";
    m_settings.frames = parse_frame_selection("0");
    m_settings.path.samples_per_pixel = 4;
    m_settings.output.transparent_background = true;
    render_animation(m_settings);

    const std::string exr = frame_file_name(m_settings.out_dir, "world_ball", 0, "exr");
    const std::vector<float> alpha = read_exr_channel(exr, "A");
    EXPECT_EQ(read_exr_channel(exr, "beauty.A"), alpha);
    const Image beauty = read_exr(exr);
    ASSERT_EQ(alpha.size(), 16u * 12);
    EXPECT_EQ(alpha[6 * 16 + 8], 1);  // the ball
    int empty = 0, edges = 0;
    for (size_t i = 0; i < alpha.size(); ++i) {
        empty += alpha[i] == 0, edges += alpha[i] > 0 && alpha[i] < 1;
        if (alpha[i] == 0) {
            EXPECT_EQ(beauty.pixels[i], Rgb{}) << i;
        }
    }
    EXPECT_GT(empty, 16 * 12 / 2);
    EXPECT_GT(edges, 4);
    const std::vector<unsigned char> png = file_bytes(frame_file_name(m_settings.out_dir, "world_ball", 0, "png"));
    EXPECT_EQ(png.at(25), 6);  // IHDR colour type: RGBA
    const DecodedImage decoded = decode_image(png.data(), png.size());
    for (size_t i = 0; i < alpha.size(); ++i) EXPECT_EQ(decoded.rgba[i * 4 + 3], std::lround(alpha[i] * 255)) << i;
    std::ifstream settings_file(settings_file_name(m_settings.out_dir, "world_ball"));
    EXPECT_EQ(nlohmann::json::parse(settings_file)["render"]["output"]["transparent_background"], true);

    // Another value is refused on resuming, as every setting the images depend on; --overwrite
    // renders the frame again, opaque: no A channel, an RGB PNG.
    m_settings.output.transparent_background = false;
    EXPECT_NE(testing::input_error_of([&] {
                  render_animation(m_settings);
              }).find("/output/transparent_background: true -> (none)"),
              std::string::npos);
    m_settings.overwrite = true;
    render_animation(m_settings);
    for (const ExrChannelInfo& channel : read_exr_channels(exr)) EXPECT_FALSE(channel.name.ends_with("A"));
    EXPECT_EQ(file_bytes(frame_file_name(m_settings.out_dir, "world_ball", 0, "png")).at(25), 2);  // RGB
    const Rgb corner = read_exr(exr).pixels[0];  // the world again (in half floats)
    EXPECT_NEAR(corner.r, 0.2f, 1e-3f);
    EXPECT_NEAR(corner.b, 0.5f, 1e-3f);
}

/// The names of the EXR's channels.
std::vector<std::string> channel_names(const std::string& exr) {
    std::vector<std::string> names;
    for (const ExrChannelInfo& channel : read_exr_channels(exr)) names.push_back(channel.name);
    return names;
}

// --layers: the localized method's analysis layers only when all are chosen, the light's terms
// unless the beauty alone is, the same values in every file that has them; and the choice is a
// setting of the folder, absent for all (what folders rendered before the option hold).
TEST_F(RenderResume, LayersChooseTheAovsAndAreASetting) {
    m_settings.method = Method::localized;
    m_settings.photon.photons = {.global_photons = 2000, .caustic_photons = 500};
    m_settings.photon.shading.samples_per_pixel = 1;
    m_settings.frames = parse_frame_selection("1");
    const std::string exr = frame_file_name(m_settings.out_dir, "ball", 1, "exr");
    // The frame rendered again (--overwrite) with each choice, its EXR kept under the choice's name.
    const auto render_with = [&](LayerSet layers) {
        m_settings.output.layers = layers;
        render_animation(m_settings);
        m_settings.overwrite = true;
        std::ifstream file(settings_file_name(m_settings.out_dir, "ball"));
        const nlohmann::json output = nlohmann::json::parse(file)["render"]["output"];
        const std::string kept = m_settings.out_dir + "/" + std::string(layer_set_name(layers)) + ".exr";
        fs::copy_file(exr, kept);
        return std::pair{kept, output};
    };
    const auto [all, all_output] = render_with(LayerSet::all);
    const auto [terms, terms_output] = render_with(LayerSet::terms);
    const auto [beauty, beauty_output] = render_with(LayerSet::beauty);

    EXPECT_EQ(channel_names(beauty), (std::vector<std::string>{"B", "G", "R", "beauty.B", "beauty.G", "beauty.R"}));
    const std::vector<std::string> term_channels = channel_names(terms);
    EXPECT_EQ(term_channels.size(), 6u + 4 * 3);
    for (const std::string& name : term_channels) {
        const std::string layer = name.substr(0, name.find('.'));
        EXPECT_TRUE(name.size() == 1 || layer == "beauty" || layer == "direct" || layer == "indirect" ||
                    layer == "caustic" || layer == "specular")
            << name;
        EXPECT_EQ(read_exr_channel(terms, name), read_exr_channel(all, name)) << name;
    }
    for (const std::string& name : channel_names(beauty))
        EXPECT_EQ(read_exr_channel(beauty, name), read_exr_channel(all, name)) << name;
    const std::vector<std::string> all_channels = channel_names(all);
    for (const std::string analysis : {"indirect_static.R", "L_y.R", "L_t.R", "influence.Y", "changed.Y"})
        EXPECT_NE(std::find(all_channels.begin(), all_channels.end(), analysis), all_channels.end()) << analysis;

    EXPECT_FALSE(all_output.contains("layers"));
    EXPECT_EQ(terms_output["layers"], "terms");
    EXPECT_EQ(beauty_output["layers"], "beauty");
    m_settings.overwrite = false;
    m_settings.output.layers = LayerSet::all;
    EXPECT_NE(
        testing::input_error_of([&] { render_animation(m_settings); }).find("/output/layers: \"beauty\" -> (none)"),
        std::string::npos);
    EXPECT_EQ(parse_layer_set("terms"), LayerSet::terms);
    EXPECT_EQ(testing::input_error_of([] { parse_layer_set("analysis"); }),
              "--layers: unknown layer set \"analysis\" (all, terms or beauty)");
}

TEST(Info, NamesMovingLightsAndTheSegmentsTheyMake) {
    const std::string text = describe_scene(std::string(STEADYLIGHT_SOURCE_DIR) + "/tests/scenes/moving_lamps.json");
    EXPECT_NE(text.find("3 at 1 fps (from the scene file) (3.00 s), 1 segment(s)"), std::string::npos) << text;
    EXPECT_NE(text.find("lights: 1 area, 1 point/spot, 1 sun, 3 animated (switched, dimmed or moved"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("spot, moves, at (1, 2.6, 1) at frame 0"), std::string::npos) << text;
    EXPECT_NE(text.find("sun, moves, travelling (0.796, -0.557, 0.239) at frame 0"), std::string::npos) << text;
}

TEST(Info, NamesAnimatedLightsAndTheSegmentsTheyMake) {
    const std::string text = describe_scene(std::string(STEADYLIGHT_SOURCE_DIR) + "/tests/scenes/light_switch.json");
    EXPECT_NE(text.find("2 segment(s): 0-9, 10-19"), std::string::npos) << text;
    EXPECT_NE(text.find("emitter, animated emission"), std::string::npos) << text;
    EXPECT_NE(text.find("lights: 1 area, 1 point/spot, 0 sun, 2 animated"), std::string::npos) << text;
    EXPECT_NE(text.find("spot, still, animated intensity, at (1, 1.5, 0)"), std::string::npos) << text;
}

}  // namespace
}  // namespace steadylight
