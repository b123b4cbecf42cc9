// Frame claims: a free frame is claimed with host and pid and released leaving nothing behind,
// a live claim is left alone, and only who takes a dead claim over removes the frame's stale
// .partial files. (Lock files themselves, of which claims are made: base/lock_file_test.cpp.)
#include "steadylight/run/frame_claim.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "support/lock_files.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;
using testing::this_host;

class FrameClaimTest : public ::testing::Test {
protected:
    void SetUp() override {
        m_dir = testing::fresh_test_folder();
        m_claim = frame_claim_name(m_dir.string(), "scene", 3);
    }
    void TearDown() override { fs::remove_all(m_dir); }

    nlohmann::json read_claim() const { return nlohmann::json::parse(std::ifstream(m_claim)); }
    LockAttempt claim() const { return try_claim_frame(m_dir.string(), "scene", 3, LockTimes{}); }

    fs::path m_dir;
    std::string m_claim;
};

TEST_F(FrameClaimTest, ClaimsAFreeFrameWithHostAndPidAndLeavesNothingWhenDone) {
    LockAttempt attempt = claim();
    ASSERT_TRUE(attempt.lock);
    EXPECT_TRUE(attempt.taken_over.empty());
    EXPECT_EQ(m_claim, (m_dir / "scene_0003.claim").string());
    EXPECT_EQ(read_claim().at("host"), this_host());
    EXPECT_EQ(read_claim().at("pid"), getpid());
    attempt.lock.reset();
    EXPECT_TRUE(fs::is_empty(m_dir)) << fs::directory_iterator(m_dir)->path();
}

TEST_F(FrameClaimTest, LeavesAFrameThatALiveProcessClaimed) {
    testing::write_lock_file(m_claim, "elsewhere", 4242, 5);
    const LockAttempt attempt = claim();
    EXPECT_FALSE(attempt.lock);
    EXPECT_NE(attempt.holder.find("host elsewhere, pid 4242, refreshed 5 s ago"), std::string::npos) << attempt.holder;
    EXPECT_EQ(read_claim().at("host"), "elsewhere");
}

TEST_F(FrameClaimTest, OnlyTheHolderRemovesTheFramesStalePartialFiles) {
    const fs::path partial = m_dir / "scene_0003.exr.partial", other = m_dir / "scene_0004.exr.partial";
    std::ofstream(partial) << "half a frame";
    std::ofstream(other) << "another frame";
    testing::write_lock_file(m_claim, "elsewhere", 4242, 0);
    EXPECT_FALSE(claim().lock);
    EXPECT_TRUE(fs::exists(partial));
    // The holder died inside the frame: who takes its claim over removes what it left.
    testing::write_lock_file(m_claim, "elsewhere", 4242, 300);
    EXPECT_TRUE(claim().lock);
    EXPECT_FALSE(fs::exists(partial));
    EXPECT_TRUE(fs::exists(other));
}

}  // namespace
}  // namespace steadylight
