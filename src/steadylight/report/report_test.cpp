// Tests of `steadylight report` on output folders made by hand: small EXRs, PNGs and statistics
// files written with the renderer's own writers, so no frame is rendered here.
#include "steadylight/report/report.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "steadylight/base/atomic_file.h"
#include "steadylight/base/error.h"
#include "steadylight/output/frame_layers.h"
#include "steadylight/output/frame_names.h"
#include "steadylight/output/image_writer.h"
#include "steadylight/passes/frame_stats.h"
#include "steadylight/report/html.h"
#include "support/input_error.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

/// A fresh, empty folder under the temporary directory.
std::string fresh_folder(const std::string& name) {
    const fs::path folder = fs::temp_directory_path() / ("steadylight_report_" + name);
    fs::remove_all(folder);
    fs::create_directories(folder);
    return folder.string();
}

FrameStats fake_stats(const std::string& method, int frame) {
    FrameStats stats;
    stats.method = method;
    stats.frame = frame;
    if (method == "path") {  // the path tracer's figures only: no photons, records or phases
        stats.camera_samples = 4 * 3 * 16;
        stats.path_rays = 1000 + 10 * frame;
        stats.path_vertices = 384;
        stats.total_s = 0.5;
        return stats;
    }
    stats.irradiance_records = method == "photon" ? 5000 + frame : 150 + 10 * frame;
    stats.photon_tracing_s = 1.0;
    stats.cache_s = method == "photon" ? 1.5 : 0.05;
    stats.influence_s = method == "photon" ? 0 : 0.1;
    stats.shading_s = 1.2;
    stats.total_s = stats.photon_tracing_s + stats.cache_s + stats.influence_s + stats.shading_s;
    return stats;
}

/// Writes what a render of `scene` with `method` writes for `frame` (without --aov).
void write_fake_frame(const std::string& dir, const std::string& scene, const std::string& method, int frame,
                      const std::string& beauty_layer = "") {
    Image beauty(4, 3), direct(4, 3);
    for (Rgb& p : beauty.pixels) p = {0.5f, 0.25f, float(frame) / 10};
    for (Rgb& p : direct.pixels) p = {0.2f, 0.2f, 0.2f};
    write_exr(frame_file_name(dir, scene, frame, "exr"),
              {{beauty_layer, &beauty}, {"direct", &direct}, {"L_y", &direct}});
    write_png(frame_file_name(dir, scene, frame, "png"), beauty);
    write_text_file(frame_file_name(dir, scene, frame, "stats.json"),
                    nlohmann::json(fake_stats(method, frame)).dump(2));
}

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

/// The number of "x,y" points of each polyline in the page, in order.
std::vector<size_t> polyline_sizes(const std::string& html) {
    static const std::regex polyline(R"re(<polyline[^>]* points="([^"]*)")re");
    std::vector<size_t> sizes;
    for (std::sregex_iterator it(html.begin(), html.end(), polyline), end; it != end; ++it)
        sizes.push_back(count((*it)[1].str(), ","));
    return sizes;
}

std::string report_of(const std::string& dir, std::optional<int> frame = std::nullopt) {
    return build_report_html({dir, frame, ""});
}

/// Frames [first, end) of BALL rendered with `method`.
struct FakeRun {
    std::string method;
    int first, end;
};

/// The report on a fresh folder `name` that holds the frames of `runs`.
std::string report_of_runs(const std::string& name, const std::vector<FakeRun>& runs) {
    const std::string dir = fresh_folder(name);
    for (const FakeRun& run : runs)
        for (int frame = run.first; frame < run.end; ++frame) write_fake_frame(dir, "ball", run.method, frame);
    return report_of(dir);
}

/// The message of the InputError that reporting on `dir` throws, or "" when it throws none.
std::string report_error(const std::string& dir) {
    return testing::input_error_of([&] { report_of(dir); });
}

TEST(Report, Base64MatchesRfc4648) {
    const auto bytes = [](const std::string& s) { return std::vector<unsigned char>(s.begin(), s.end()); };
    EXPECT_EQ(encode_base64(bytes("")), "");
    EXPECT_EQ(encode_base64(bytes("M")), "TQ==");
    EXPECT_EQ(encode_base64(bytes("Ma")), "TWE=");
    EXPECT_EQ(encode_base64(bytes("Man")), "TWFu");
    EXPECT_EQ(encode_base64({0xff, 0xfe, 0x00, 0x01}), "//4AAQ==");
}

TEST(Report, FrameStatsRoundTripThroughJson) {
    const FrameStats stats = fake_stats("localized", 7);
    const FrameStats back = nlohmann::json(stats).get<FrameStats>();
    EXPECT_EQ(nlohmann::json(back), nlohmann::json(stats));
}

TEST(Report, MissingFolderIsAnInputError) {
    EXPECT_NE(report_error("/nonexistent/steadylight/out").find("no such folder"), std::string::npos);
}

TEST(Report, FolderWithoutFramesIsAnInputError) {
    const std::string dir = fresh_folder("empty");
    write_text_file(dir + "/notes.txt", "nothing here");
    EXPECT_NE(report_error(dir).find("no frames found"), std::string::npos);
}

TEST(Report, ListsEveryFrameInTheContactSheet) {
    const std::string dir = fresh_folder("frames");
    for (int frame = 0; frame < 5; ++frame) write_fake_frame(dir, "ball", "localized", frame);
    write_png(dir + "/ball_0002.direct.png", Image(4, 3));  // an --aov PNG is no frame
    const std::string html = report_of(dir);
    for (int frame = 0; frame < 5; ++frame)
        EXPECT_EQ(count(html, "<figure class=\"frame\" data-frame=\"" + std::to_string(frame) + "\">"), 1u) << frame;
    EXPECT_EQ(count(html, "<figure class=\"frame\""), 5u);
    EXPECT_EQ(count(html, "<img src=\"data:image/png;base64,"), 5u + 3u);  // thumbnails + AOVs of one frame
    // Nothing is fetched: no external sources, links, imports or fonts.
    for (const char* fetch : {"src=\"http", "href=", "@import", "url(", "<link"})
        EXPECT_EQ(html.find(fetch), std::string::npos) << fetch;
}

TEST(Report, PlotsHaveOnePointPerFrameForEachMethod) {
    const std::string html = report_of_runs("methods", {{"photon", 0, 4}, {"localized", 4, 10}});
    const std::vector<size_t> sizes = polyline_sizes(html);
    // time per frame, records and photon paths traced: photon then localized; then the phases
    // of each method (the fake frames have no pixel counts: no plot of them).
    ASSERT_GE(sizes.size(), 6u);
    for (size_t plot = 0; plot < 3; ++plot) {
        EXPECT_EQ(sizes[2 * plot], 4u) << plot;
        EXPECT_EQ(sizes[2 * plot + 1], 6u) << plot;
    }
    EXPECT_EQ(sizes.size(), 6u + 4u + 5u);  // photon: 4 phases with time; localized: 5
    for (const size_t size : sizes) EXPECT_GT(size, 0u);
}

TEST(Report, TablesNameEachMethodAndCompareWithPhoton) {
    const std::string html = report_of_runs("tables", {{"photon", 0, 2}, {"localized", 2, 4}});
    EXPECT_NE(html.find("<th>photon</th><th>localized</th><th>photon / localized</th>"), std::string::npos);
    // Records: photon 5000.5, localized 175 a frame.
    EXPECT_NE(html.find("<th>irradiance records computed</th><td>5000.5</td><td>175.0</td><td>28.57x</td>"),
              std::string::npos);
    // The photon method has no influence phase: nothing to compare.
    EXPECT_NE(html.find("<th>influence (s)</th><td>0</td><td>0.100</td><td>&mdash;</td>"), std::string::npos);
}

TEST(Report, ScenesAreKeptApart) {
    const std::string dir = fresh_folder("scenes");
    for (int frame = 0; frame < 3; ++frame) write_fake_frame(dir, "ball", "localized", frame);
    for (int frame = 0; frame < 2; ++frame) write_fake_frame(dir, "table", "localized", frame);
    const std::string html = report_of(dir);
    EXPECT_EQ(count(html, "<table class=\"summary\""), 2u);
    EXPECT_NE(html.find("data-series=\"ball \u00b7 localized\""), std::string::npos);
    EXPECT_NE(html.find("<div class=\"sheet\" data-scene=\"table\">"), std::string::npos);
    EXPECT_EQ(polyline_sizes(html)[0], 3u);
    EXPECT_EQ(polyline_sizes(html)[1], 2u);
}

TEST(Report, AovsOfTheMiddleFrameByDefault) {
    const std::string dir = fresh_folder("aovs");
    for (int frame = 10; frame < 13; ++frame) write_fake_frame(dir, "ball", "localized", frame);
    const std::string html = report_of(dir);
    EXPECT_NE(html.find("ball, frame 11</h3>"), std::string::npos);
    for (const char* layer : {"beauty", "direct", "L_y"})
        EXPECT_EQ(count(html, std::string("<figure class=\"aov\" data-layer=\"") + layer + "\">"), 1u) << layer;
    EXPECT_NE(report_of(dir, 12).find("ball, frame 12</h3>"), std::string::npos);
    EXPECT_THROW(report_of(dir, 99), InputError);
}

TEST(Report, ANamedBeautyLayerShowsAsBeauty) {
    const std::string dir = fresh_folder("beauty");
    write_fake_frame(dir, "ball", "photon", 0, "beauty");
    const std::string html = report_of(dir);
    EXPECT_EQ(count(html, "data-layer=\"beauty\""), 1u);
    EXPECT_EQ(count(html, "<figure class=\"aov\""), 3u);
    EXPECT_LT(html.find("data-layer=\"beauty\""), html.find("data-layer=\"L_y\""));  // first, though "L" < "b"
}

TEST(Report, AFramesBeautyShowsOnceAndGreyLayersShowToo) {
    const std::string dir = fresh_folder("frame_layers");
    Image beauty(4, 3);
    for (Rgb& p : beauty.pixels) p = {0.5f, 0.25f, 0.1f};
    GreyImage influence(4, 3);
    std::fill(influence.pixels.begin(), influence.pixels.end(), 1.0f);
    // As render writes it: the beauty unnamed and as `beauty`, `influence` as the one channel Y.
    write_exr(frame_file_name(dir, "ball", 0, "exr"),
              frame_exr_layers(beauty, {{"direct", beauty}, {"influence", influence}}));
    const std::string html = report_of(dir);
    EXPECT_EQ(count(html, "data-layer=\"beauty\""), 1u);
    EXPECT_EQ(count(html, "<figure class=\"aov\" data-layer=\"influence\">"), 1u);
    EXPECT_EQ(count(html, "<figure class=\"aov\""), 3u);
    EXPECT_EQ(count(html, "aov-skipped"), 0u);
}

TEST(Report, FramesWithoutStatisticsAreShownButNotPlotted) {
    const std::string dir = fresh_folder("path");
    write_fake_frame(dir, "ball", "path", 0);
    fs::remove(frame_file_name(dir, "ball", 0, "stats.json"));
    const std::string html = report_of(dir);
    EXPECT_EQ(count(html, "<figure class=\"frame\""), 1u);
    EXPECT_TRUE(polyline_sizes(html).empty());
    EXPECT_NE(html.find("No frame statistics"), std::string::npos);
}

TEST(Report, PathFramesArePlottedAndComparedWithPhoton) {
    const std::string html = report_of_runs("path_stats", {{"photon", 0, 2}, {"path", 2, 5}});
    EXPECT_EQ(html.find("No frame statistics"), std::string::npos);
    // The time per frame: a line per method, the path tracer's with a point per frame.
    const std::vector<size_t> sizes = polyline_sizes(html);
    ASSERT_GE(sizes.size(), 2u);
    EXPECT_EQ(sizes[0], 2u);
    EXPECT_EQ(sizes[1], 3u);
    EXPECT_NE(html.find("data-series=\"path\""), std::string::npos);
    EXPECT_NE(html.find("time per phase: path"), std::string::npos);
    // The table: the path tracer's figures, and photon figures it lacks shown as 0.
    EXPECT_NE(html.find("<th>photon</th><th>path</th><th>photon / path</th>"), std::string::npos);
    EXPECT_NE(html.find("<th>total (s)</th><td>3.700</td><td>0.500</td><td>7.40x</td>"), std::string::npos);
    EXPECT_NE(html.find("<th>irradiance records computed</th><td>5000.5</td><td>0</td><td>&mdash;</td>"),
              std::string::npos);
    EXPECT_NE(html.find("<th>camera samples (path)</th><td>0</td><td>192.0</td><td>&mdash;</td>"), std::string::npos);
    EXPECT_NE(html.find("<th>rays traced (path)</th><td>0</td><td>1030.0</td>"), std::string::npos);
    EXPECT_NE(html.find("<th>path length (vertices a sample)</th><td>0</td><td>2.000</td>"), std::string::npos);
    EXPECT_NE(html.find("path &middot; 0.50 s"), std::string::npos);  // the contact sheet's caption
}

TEST(Report, StatisticsWithoutPathFiguresFromOlderRunsStillRead) {
    const std::string dir = fresh_folder("older_stats");
    write_fake_frame(dir, "ball", "localized", 0);
    nlohmann::json older = fake_stats("localized", 0);
    older.erase("path");
    write_text_file(frame_file_name(dir, "ball", 0, "stats.json"), older.dump(2));
    std::string html;
    ASSERT_NO_THROW(html = report_of(dir));
    EXPECT_NE(html.find("<th>localized</th>"), std::string::npos);
    EXPECT_NE(html.find("<th>camera samples (path)</th><td>0</td>"), std::string::npos);
}

TEST(Report, CorruptStatisticsNameTheFile) {
    const std::string dir = fresh_folder("bad_stats");
    write_fake_frame(dir, "ball", "localized", 0);
    write_text_file(frame_file_name(dir, "ball", 0, "stats.json"), "{\"method\": \"localized\", \"fra");
    EXPECT_NE(report_error(dir).find("ball_0000.stats.json: not a frame statistics file"), std::string::npos)
        << report_error(dir);
}

TEST(Report, CorruptExrNamesTheFile) {
    const std::string dir = fresh_folder("bad_exr");
    write_fake_frame(dir, "ball", "localized", 0);
    write_text_file(frame_file_name(dir, "ball", 0, "exr"), "not an EXR");
    EXPECT_NE(report_error(dir).find("ball_0000.exr: cannot read EXR"), std::string::npos) << report_error(dir);
}

TEST(Report, IsWrittenWholeBesideTheFrames) {
    const std::string dir = fresh_folder("write");
    write_fake_frame(dir, "ball", "localized", 0);
    EXPECT_EQ(write_report({dir, std::nullopt, ""}), dir + "/report.html");
    EXPECT_GT(fs::file_size(dir + "/report.html"), 1000u);
    EXPECT_FALSE(fs::exists(dir + "/report.html.partial"));
    // A second report ignores the first one.
    EXPECT_NO_THROW(write_report({dir, std::nullopt, dir + "/again.html"}));
    EXPECT_THROW(write_report({dir, std::nullopt, "/nonexistent/folder/report.html"}), InputError);
}

}  // namespace
}  // namespace steadylight
