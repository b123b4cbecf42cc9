// Tests of the frame statistics file (`<scene>_<frame>.stats.json`) and the console line.
#include "steadylight/passes/frame_stats.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace steadylight {
namespace {

FrameStats path_stats() {
    FrameStats stats;
    stats.method = "path";
    stats.frame = 4;
    stats.camera_samples = 2'000'000;
    stats.path_rays = 9'000'000;
    stats.path_vertices = 5'000'000;
    stats.total_s = 3.5;
    return stats;
}

FrameStats photon_stats() {
    FrameStats stats;
    stats.method = "photon";
    stats.global_photons_emitted = 20'000;
    stats.global_photons_stored = 15'000;
    stats.irradiance_records = 300;
    stats.retraced_photon_paths = 1234;
    stats.photon_tracing_s = 0.5;
    stats.cache_s = 1.0;
    stats.shading_s = 0.75;
    stats.total_s = 2.25;
    return stats;
}

TEST(FrameStats, PathFiguresRoundTripThroughJson) {
    const nlohmann::json json = path_stats();
    EXPECT_EQ(json.at("path").at("camera_samples"), 2'000'000);
    EXPECT_EQ(json.at("path").at("rays"), 9'000'000);
    EXPECT_EQ(json.at("path").at("vertices"), 5'000'000);
    EXPECT_EQ(nlohmann::json(json.get<FrameStats>()), json);
}

/// A stats.json written before the path tracer had statistics lacks the "path" figures (and
/// one from before photon paths were reused, the paths traced): it still reads, with zeros there.
TEST(FrameStats, OlderFileWithoutPathFiguresReadsThemAsZero) {
    nlohmann::json older = photon_stats();
    older.erase("path");
    older["photons"].erase("retraced_paths");
    ASSERT_FALSE(older.contains("path"));
    const FrameStats read = older.get<FrameStats>();
    EXPECT_EQ(read.camera_samples, 0);
    EXPECT_EQ(read.path_rays, 0);
    EXPECT_EQ(read.path_vertices, 0);
    EXPECT_EQ(read.retraced_photon_paths, 0);
    EXPECT_EQ(read.irradiance_records, 300);
    EXPECT_EQ(read.total_s, 2.25);
}

/// The shading time's key was /seconds/direct before it was named for what it holds: such files
/// still read, the report among their readers.
TEST(FrameStats, OlderFileWithSecondsDirectReadsItAsTheShadingTime) {
    const nlohmann::json current = photon_stats();
    EXPECT_EQ(current.at("seconds").at("shading"), 0.75);
    EXPECT_FALSE(current.at("seconds").contains("direct"));
    nlohmann::json older = current;
    older["seconds"].erase("shading");
    older["seconds"]["direct"] = 0.5;
    EXPECT_EQ(older.get<FrameStats>().shading_s, 0.5);
    nlohmann::json neither = current;
    neither["seconds"].erase("shading");
    EXPECT_THROW(neither.get<FrameStats>(), nlohmann::json::exception);
}

TEST(FrameStats, FieldsOfTheFirstFilesAreStillRequired) {
    nlohmann::json without_total = path_stats();
    without_total["seconds"].erase("total");
    EXPECT_THROW(without_total.get<FrameStats>(), nlohmann::json::exception);
    nlohmann::json wrong_type = path_stats();
    wrong_type["path"]["rays"] = "many";
    EXPECT_THROW(wrong_type.get<FrameStats>(), nlohmann::json::exception);
}

/// The console line shows each group of figures only for frames that have it.
TEST(FrameStats, SummaryShowsTheFiguresTheFrameHas) {
    struct Case {
        FrameStats stats;
        std::vector<std::string> shown, left_out;
    };
    const Case cases[] = {
        {path_stats(),
         {"camera samples 2.00M", "rays 9.00M (4.50 a sample)", "path length 2.50 vertices"},
         {"photons"}},
        {photon_stats(),
         {"photons 15k/0k stored, records 300", "photon paths traced 1234", "shading 0.75 s"},
         {"camera samples", "influence"}},
    };
    for (const Case& c : cases) {
        const std::string line = summarize(c.stats);
        for (const std::string& part : c.shown) EXPECT_NE(line.find(part), std::string::npos) << line;
        for (const std::string& part : c.left_out) EXPECT_EQ(line.find(part), std::string::npos) << line;
    }
}

}  // namespace
}  // namespace steadylight
