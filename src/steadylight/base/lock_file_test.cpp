// Lock files: mutual exclusion between processes (a counter incremented under the lock loses no
// update), a waiter gets the lock when its holder releases it, of several processes that find
// one dead lock exactly one takes it over, dead break files are taken over and live ones
// respected, a holder refreshes its file and releases only its own, and nothing is followed
// through a symbolic link or blocks on a FIFO.
#include "steadylight/base/lock_file.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <array>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <thread>
#include <vector>

#include "steadylight/base/error.h"
#include "steadylight/base/stopwatch.h"
#include "support/lock_files.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;
using testing::this_host;
using testing::write_lock_file;

class LockFileTest : public ::testing::Test {
protected:
    void SetUp() override {
        m_dir = testing::fresh_test_folder();
        m_lock = (m_dir / "x.lock").string();
    }
    void TearDown() override { fs::remove_all(m_dir); }

    static pid_t gone_pid() {
        const pid_t child = fork();
        if (child == 0) _exit(0);
        waitpid(child, nullptr, 0);
        return child;
    }
    /// Runs `body` in `count` child processes at once; returns their exit statuses.
    static std::vector<int> in_processes(int count, const std::function<int()>& body) {
        std::vector<pid_t> children;
        for (int i = 0; i < count; ++i) {
            const pid_t child = fork();
            if (child == 0) _exit(body());
            children.push_back(child);
        }
        std::vector<int> statuses;
        for (const pid_t child : children) {
            int status = 0;
            waitpid(child, &status, 0);
            statuses.push_back(WIFEXITED(status) ? WEXITSTATUS(status) : -1);
        }
        return statuses;
    }
    std::vector<std::string> leftovers() const {
        std::vector<std::string> names;
        for (const fs::directory_entry& entry : fs::directory_iterator(m_dir))
            names.push_back(entry.path().filename().string());
        return names;
    }

    fs::path m_dir;
    std::string m_lock;
};

TEST_F(LockFileTest, ProcessesIncrementingACounterUnderTheLockLoseNoUpdate) {
    const std::string counter = (m_dir / "counter").string();
    std::ofstream(counter) << 0;
    const LockTimes times{0.05, 5};
    const std::vector<int> statuses = in_processes(4, [&] {
        for (int i = 0; i < 25; ++i) {
            const std::unique_ptr<LockFile> lock = LockFile::lock(m_lock, "the counter", times);
            int value = 0;
            std::ifstream(counter) >> value;
            std::this_thread::sleep_for(std::chrono::microseconds(200));
            std::ofstream(counter) << value + 1;
        }
        return 0;
    });
    EXPECT_EQ(statuses, std::vector<int>(4, 0));
    int value = 0;
    std::ifstream(counter) >> value;
    EXPECT_EQ(value, 100);
    EXPECT_EQ(leftovers(), std::vector<std::string>{"counter"});
}

TEST_F(LockFileTest, AWaiterGetsTheLockWhenItsHolderReleasesIt) {
    int ready[2];
    ASSERT_EQ(pipe(ready), 0);
    const pid_t child = fork();
    if (child == 0) {
        {
            const std::unique_ptr<LockFile> lock = LockFile::lock(m_lock, "the test");
            (void)!write(ready[1], "x", 1);
            std::this_thread::sleep_for(std::chrono::milliseconds(500));
        }
        _exit(0);
    }
    ASSERT_GT(child, 0);
    char byte = 0;
    ASSERT_EQ(read(ready[0], &byte, 1), 1);
    EXPECT_FALSE(LockFile::try_lock(m_lock).lock);
    const Stopwatch time;
    {
        const std::unique_ptr<LockFile> lock = LockFile::lock(m_lock, "the test");
        EXPECT_GT(time.elapsed_s(), 0.3);
        EXPECT_LT(time.elapsed_s(), 5);  // released, not taken over as dead
        EXPECT_EQ(nlohmann::json::parse(std::ifstream(m_lock)).at("pid"), getpid());
    }
    EXPECT_FALSE(fs::exists(m_lock));
    waitpid(child, nullptr, 0);
    close(ready[0]);
    close(ready[1]);
}

TEST_F(LockFileTest, OfProcessesThatFindOneDeadLockExactlyOneTakesItOver) {
    for (int round = 0; round < 5; ++round) {
        write_lock_file(m_lock, "elsewhere", 4242, 300);
        const std::vector<int> statuses = in_processes(4, [&] {
            const LockAttempt attempt = LockFile::try_lock(m_lock, {10, 120});
            // Hold it until the others have tried.
            std::this_thread::sleep_for(std::chrono::milliseconds(300));
            return attempt.lock && !attempt.taken_over.empty() ? 1 : 0;
        });
        int taken = 0;
        for (const int status : statuses) taken += status;
        EXPECT_EQ(taken, 1) << "round " << round;
        EXPECT_FALSE(fs::exists(m_lock));
    }
}

TEST_F(LockFileTest, TakesOverAtOnceTheLockOfAProcessOfThisHostThatIsGone) {
    const pid_t gone = gone_pid();
    write_lock_file(m_lock, this_host(), gone, 1);
    const LockAttempt attempt = LockFile::try_lock(m_lock);
    ASSERT_TRUE(attempt.lock);
    EXPECT_NE(attempt.taken_over.find(fmt::format("its process {} on this host is gone", gone)), std::string::npos)
        << attempt.taken_over;
}

TEST_F(LockFileTest, TakesOverAnEmptyLockFileLeftByAnOlderSteadylight) {
    std::ofstream{m_lock};
    const LockAttempt attempt = LockFile::try_lock(m_lock);
    ASSERT_TRUE(attempt.lock);
    EXPECT_NE(attempt.taken_over.find("an empty lock file"), std::string::npos) << attempt.taken_over;
}

TEST_F(LockFileTest, ALiveBreakFileKeepsOthersFromTakingADeadLockOver) {
    write_lock_file(m_lock, "elsewhere", 4242, 300);
    write_lock_file(m_lock + ".break", "elsewhere", 4243, 0);
    LockAttempt attempt = LockFile::try_lock(m_lock, {10, 120});
    EXPECT_FALSE(attempt.lock);
    EXPECT_NE(attempt.holder.find("being taken over by another process"), std::string::npos) << attempt.holder;
    // A break whose holder died before removing it is dead by the same rules.
    write_lock_file(m_lock + ".break", this_host(), gone_pid(), 0);
    attempt = LockFile::try_lock(m_lock, {10, 120});
    ASSERT_TRUE(attempt.lock);
    EXPECT_NE(attempt.taken_over.find("not refreshed for 300 s, the limit is 120 s"), std::string::npos)
        << attempt.taken_over;
    attempt.lock.reset();
    EXPECT_TRUE(leftovers().empty()) << leftovers().front();
}

TEST_F(LockFileTest, ASymbolicLinkOrAFifoWhereTheLockGoesIsAnErrorNotFollowed) {
    const fs::path target = m_dir / "elsewhere";
    fs::create_symlink(target, m_lock);
    try {
        LockFile::try_lock(m_lock);
        FAIL() << "no error";
    } catch (const OutputError& e) {
        EXPECT_NE(std::string(e.what()).find(m_lock + ": cannot open it as a lock file"), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("symbolic link"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(target));
    fs::remove(m_lock);
    ASSERT_EQ(mkfifo(m_lock.c_str(), 0600), 0);
    EXPECT_THROW(LockFile::try_lock(m_lock), OutputError);
}

TEST_F(LockFileTest, TheHolderRefreshesItsLockFile) {
    const LockAttempt attempt = LockFile::try_lock(m_lock, {0.05, 120});
    ASSERT_TRUE(attempt.lock);
    const std::string token = nlohmann::json::parse(std::ifstream(m_lock)).at("token");
    utimensat(AT_FDCWD, m_lock.c_str(), std::array<timespec, 2>{timespec{1, 0}, timespec{1, 0}}.data(), 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(400));
    EXPECT_LT(testing::file_age_s(m_lock), 10);
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(m_lock)).at("token"), token);  // its content unchanged
}

TEST_F(LockFileTest, LeavesInPlaceALockThatAnotherProcessTookOver) {
    LockAttempt attempt = LockFile::try_lock(m_lock);
    ASSERT_TRUE(attempt.lock);
    write_lock_file(m_lock, "elsewhere", 4242, 0);
    attempt.lock.reset();
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(m_lock)).at("host"), "elsewhere");
}

TEST_F(LockFileTest, NamesTheFileItCannotWrite) {
    try {
        LockFile::try_lock("/nonexistent/folder/x.lock");
        FAIL() << "no error";
    } catch (const OutputError& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/folder/x.lock"), std::string::npos) << e.what();
    }
}

TEST(LockTimes, TestsSetThemThroughTheEnvironmentAndAMalformedValueIsAnError) {
    unsetenv("STEADYLIGHT_TEST_LOCK_TIMES");
    EXPECT_EQ(lock_times().stale_s, 120);
    setenv("STEADYLIGHT_TEST_LOCK_TIMES", "0.5,4", 1);
    EXPECT_EQ(lock_times().refresh_s, 0.5);
    EXPECT_EQ(lock_times().stale_s, 4);
    for (const char* bad : {"4", "4,0.5", "0,4", "0.5,4,1", "x,y", "0.5,inf"}) {
        setenv("STEADYLIGHT_TEST_LOCK_TIMES", bad, 1);
        EXPECT_THROW(lock_times(), InputError) << bad;
    }
    unsetenv("STEADYLIGHT_TEST_LOCK_TIMES");
}

}  // namespace
}  // namespace steadylight
