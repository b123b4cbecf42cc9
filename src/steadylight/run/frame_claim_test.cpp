// Frame claims: a free frame is claimed and released, a live claim is left alone, dead ones
// (a process of this host that is gone, a file not refreshed in time) are taken over, the
// holder refreshes its file, and only the holder removes a frame's stale .partial files.
#include "steadylight/run/frame_claim.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

namespace steadylight {
namespace {

namespace fs = std::filesystem;

std::string this_host() {
    char name[256] = {};
    gethostname(name, sizeof name - 1);
    return name;
}

class FrameClaimTest : public ::testing::Test {
protected:
    void SetUp() override {
        m_dir = fs::temp_directory_path() / fmt::format("steadylight_claim_{}_{}",
                                                        ::testing::UnitTest::GetInstance()->current_test_info()->name(),
                                                        getpid());
        fs::remove_all(m_dir);
        fs::create_directories(m_dir);
        m_claim = frame_claim_name(m_dir.string(), "scene", 3);
    }
    void TearDown() override { fs::remove_all(m_dir); }

    /// A claim file as another process wrote it, last touched `age_s` ago.
    void write_claim(const std::string& host, int pid, double age_s = 0) const {
        std::ofstream(m_claim) << nlohmann::json{{"host", host}, {"pid", pid}, {"time", "then"}}.dump();
        const auto then = std::chrono::system_clock::now() - std::chrono::duration<double>(age_s);
        const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(then.time_since_epoch()).count();
        const timespec times[2] = {{ns / 1'000'000'000, ns % 1'000'000'000}, {ns / 1'000'000'000, ns % 1'000'000'000}};
        ASSERT_EQ(utimensat(AT_FDCWD, m_claim.c_str(), times, 0), 0);
    }
    double claim_age_s() const {
        return std::chrono::duration<double>(fs::file_time_type::clock::now() - fs::last_write_time(m_claim)).count();
    }
    nlohmann::json read_claim() const { return nlohmann::json::parse(std::ifstream(m_claim)); }

    ClaimAttempt claim(double stale_s = claim_stale_s, double refresh_s = claim_refresh_s) const {
        return try_claim_frame(m_dir.string(), "scene", 3, stale_s, refresh_s);
    }

    fs::path m_dir;
    std::string m_claim;
};

TEST_F(FrameClaimTest, ClaimsAFreeFrameWithHostAndPidAndRemovesTheClaimWhenDone) {
    ClaimAttempt attempt = claim();
    ASSERT_TRUE(attempt.claim);
    EXPECT_TRUE(attempt.taken_over.empty());
    EXPECT_EQ(m_claim, (m_dir / "scene_0003.claim").string());
    EXPECT_EQ(read_claim().at("host"), this_host());
    EXPECT_EQ(read_claim().at("pid"), getpid());
    attempt.claim.reset();
    EXPECT_FALSE(fs::exists(m_claim));
    EXPECT_TRUE(fs::exists(m_dir / ".steadylight.lock"));
}

TEST_F(FrameClaimTest, LeavesAFrameThatALiveProcessClaimed) {
    write_claim("elsewhere", 4242, 5);
    const ClaimAttempt attempt = claim();
    EXPECT_FALSE(attempt.claim);
    EXPECT_NE(attempt.holder.find("host elsewhere, pid 4242, refreshed 5 s ago"), std::string::npos) << attempt.holder;
    EXPECT_EQ(read_claim().at("host"), "elsewhere");
}

TEST_F(FrameClaimTest, ASecondClaimInTheSameFolderIsRefusedWhileTheFirstIsHeld) {
    const ClaimAttempt first = claim();
    ASSERT_TRUE(first.claim);
    const ClaimAttempt second = claim();
    EXPECT_FALSE(second.claim);
    EXPECT_NE(second.holder.find(fmt::format("pid {}", getpid())), std::string::npos) << second.holder;
}

TEST_F(FrameClaimTest, TakesOverAtOnceTheClaimOfAProcessOfThisHostThatIsGone) {
    const pid_t child = fork();
    if (child == 0) _exit(0);
    ASSERT_GT(child, 0);
    waitpid(child, nullptr, 0);
    write_claim(this_host(), child, 1);
    const ClaimAttempt attempt = claim();
    ASSERT_TRUE(attempt.claim);
    EXPECT_NE(attempt.taken_over.find(fmt::format("its process {} on this host is gone", child)), std::string::npos)
        << attempt.taken_over;
    EXPECT_EQ(read_claim().at("pid"), getpid());
}

TEST_F(FrameClaimTest, TakesOverAClaimNotRefreshedWithinTheLimit) {
    write_claim("elsewhere", 4242, 200);
    const ClaimAttempt attempt = claim(120);
    ASSERT_TRUE(attempt.claim);
    EXPECT_NE(attempt.taken_over.find("not refreshed for 200 s, the limit is 120 s"), std::string::npos)
        << attempt.taken_over;
    EXPECT_EQ(read_claim().at("host"), this_host());
}

TEST_F(FrameClaimTest, TheHolderRefreshesItsClaim) {
    const ClaimAttempt attempt = claim(claim_stale_s, 0.05);
    ASSERT_TRUE(attempt.claim);
    write_claim(this_host(), getpid(), 100);
    std::this_thread::sleep_for(std::chrono::milliseconds(400));
    EXPECT_LT(claim_age_s(), 10);
}

TEST_F(FrameClaimTest, LeavesInPlaceAClaimThatAnotherProcessTookOver) {
    ClaimAttempt attempt = claim();
    ASSERT_TRUE(attempt.claim);
    write_claim("elsewhere", 4242);
    attempt.claim.reset();
    EXPECT_EQ(read_claim().at("host"), "elsewhere");
}

TEST_F(FrameClaimTest, OnlyTheHolderRemovesTheFramesStalePartialFiles) {
    const fs::path partial = m_dir / "scene_0003.exr.partial", other = m_dir / "scene_0004.exr.partial";
    std::ofstream(partial) << "half a frame";
    std::ofstream(other) << "another frame";
    write_claim("elsewhere", 4242);
    EXPECT_FALSE(claim().claim);
    EXPECT_TRUE(fs::exists(partial));
    // The holder died inside the frame: who takes its claim over removes what it left.
    write_claim("elsewhere", 4242, 300);
    EXPECT_TRUE(claim().claim);
    EXPECT_FALSE(fs::exists(partial));
    EXPECT_TRUE(fs::exists(other));
}

}  // namespace
}  // namespace steadylight
