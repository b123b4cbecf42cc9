// Resume logic: which frames count as complete, and why the others do not.
#include "steadylight/run/frame_manifest.h"

#include <gtest/gtest.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include <filesystem>
#include <fstream>

#include "steadylight/base/atomic_file.h"
#include "steadylight/output/frame_names.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

/// A fresh folder with frame 3 of scene "s" written as two files and its manifest.
class FrameManifest : public ::testing::Test {
protected:
    void SetUp() override {
        // One folder per test and process: ctest runs tests in parallel, maybe from several checkouts.
        m_dir = (fs::temp_directory_path() /
                 fmt::format("steadylight_manifest_{}_{}",
                             ::testing::UnitTest::GetInstance()->current_test_info()->name(), getpid()))
                    .string();
        fs::remove_all(m_dir);
        fs::create_directories(m_dir);
        const WrittenFiles written;
        write_text_file(file("exr"), std::string(1000, 'x'));
        write_text_file(file("png"), "png bytes");
        write_frame_manifest(m_dir, "s", 3, written.paths(), "key1");
    }
    void TearDown() override { fs::remove_all(m_dir); }

    std::string file(const std::string& extension) const { return frame_file_name(m_dir, "s", 3, extension); }
    FrameCheck check(const std::string& key = "key1") const { return check_frame_outputs(m_dir, "s", 3, key); }

    std::string m_dir;
};

TEST_F(FrameManifest, FrameWithoutManifestIsNotRenderedAndSaysNothing) {
    const FrameCheck other = check_frame_outputs(m_dir, "s", 4, "key1");
    EXPECT_FALSE(other.complete);
    EXPECT_EQ(other.problem, "");
}

TEST_F(FrameManifest, WrittenFrameIsComplete) {
    EXPECT_TRUE(check().complete) << check().problem;
    EXPECT_TRUE(fs::exists(frame_manifest_name(m_dir, "s", 3)));
}

TEST_F(FrameManifest, TruncatedFileIsIncomplete) {
    fs::resize_file(file("exr"), 500);
    EXPECT_FALSE(check().complete);
    EXPECT_EQ(check().problem, "s_0003.exr has 500 bytes, 1000 were written");
}

TEST_F(FrameManifest, ChangedOrMissingFileIsIncomplete) {
    std::ofstream(file("png"), std::ios::binary) << "PNG BYTES";  // same size, other bytes
    EXPECT_EQ(check().problem, "s_0003.png has changed since it was written");
    fs::remove(file("png"));
    EXPECT_EQ(check().problem, "s_0003.png is missing");
}

TEST_F(FrameManifest, OtherSettingsKeyIsIncomplete) {
    EXPECT_FALSE(check("key2").complete);
    EXPECT_EQ(check("key2").problem, "it was rendered with other settings");
}

TEST_F(FrameManifest, ManifestNamingFilesOutsideTheFolderIsIncomplete) {
    // /dev/zero has size 0: checking it would read forever.
    for (const std::string name : {"/dev/zero", "../s_0003.png", "sub/../../s_0003.png", ""}) {
        const nlohmann::json manifest = {{"settings_key", "key1"},
                                         {"files", {{{"name", name}, {"bytes", 0}, {"checksum", "0"}}}}};
        write_text_file(frame_manifest_name(m_dir, "s", 3), manifest.dump());
        EXPECT_EQ(check().problem, "its manifest names \"" + name + "\"");
    }
}

TEST_F(FrameManifest, ByteCountThatIsNotACountIsIncomplete) {
    // 1e42 is read as a float, whose conversion to an integer would be undefined (a fuzzing finding).
    for (const nlohmann::json& bytes : {nlohmann::json(6.3e42), nlohmann::json(-1), nlohmann::json("1000")}) {
        const nlohmann::json manifest = {{"settings_key", "key1"},
                                         {"files", {{{"name", "s_0003.exr"}, {"bytes", bytes}, {"checksum", "0"}}}}};
        write_text_file(frame_manifest_name(m_dir, "s", 3), manifest.dump());
        EXPECT_EQ(check().problem, "its manifest gives s_0003.exr no byte count") << bytes;
    }
}

TEST_F(FrameManifest, DamagedManifestIsIncomplete) {
    fs::resize_file(frame_manifest_name(m_dir, "s", 3), 20);
    EXPECT_FALSE(check().complete);
    EXPECT_NE(check().problem.find("s_0003.manifest.json is damaged"), std::string::npos);
}

TEST(WrittenFiles, RecordsOnlyWhileAlive) {
    const std::string path = (fs::temp_directory_path() / fmt::format("steadylight_written_{}.txt", getpid())).string();
    {
        const WrittenFiles written;
        write_text_file(path, "a");
        EXPECT_EQ(written.paths(), std::vector<std::string>{path});
    }
    const WrittenFiles later;
    EXPECT_TRUE(later.paths().empty());
    fs::remove(path);
}

}  // namespace
}  // namespace steadylight
