// FileLock: a second process waits until the first releases the lock.
#include "steadylight/base/file_lock.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "steadylight/base/stopwatch.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

TEST(FileLock, ASecondProcessWaitsUntilTheFirstReleasesIt) {
    const fs::path path = fs::temp_directory_path() / fmt::format("steadylight_lock_{}.lock", getpid());
    int ready[2];
    ASSERT_EQ(pipe(ready), 0);
    const pid_t child = fork();
    if (child == 0) {
        // The child holds the lock for 0.5 s.
        const FileLock lock(path.string());
        (void)!write(ready[1], "x", 1);
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
        _exit(0);
    }
    ASSERT_GT(child, 0);
    char byte = 0;
    ASSERT_EQ(read(ready[0], &byte, 1), 1);
    const Stopwatch time;
    {
        const FileLock lock(path.string());
        EXPECT_GT(time.elapsed_s(), 0.3);
    }
    waitpid(child, nullptr, 0);
    close(ready[0]);
    close(ready[1]);
    fs::remove(path);
}

TEST(FileLock, NamesTheFileItCannotOpen) {
    try {
        const FileLock lock("/nonexistent/folder/x.lock");
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/folder/x.lock"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace steadylight
