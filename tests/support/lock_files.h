// For tests of lock files and the frame claims made of them (base/lock_file.h): a folder of the
// test's own, and lock files as other processes wrote them.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

namespace steadylight::testing {

inline std::string this_host() {
    char name[256] = {};
    gethostname(name, sizeof name - 1);
    return name;
}

/// An empty folder for the running test, `<tmp>/steadylight_<suite>.<test>_<pid>`: ctest runs
/// tests in parallel, maybe from several checkouts.
inline std::filesystem::path fresh_test_folder() {
    const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() /
        (std::string("steadylight_") + test->test_suite_name() + "." + test->name() + "_" + std::to_string(getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

/// A lock file at `path` as the process `pid` of `host` wrote it, last refreshed `age_s` ago.
inline void write_lock_file(const std::string& path, const std::string& host, int pid, double age_s) {
    std::ofstream(path) << nlohmann::json{{"host", host}, {"pid", pid}, {"time", "then"}}.dump();
    const auto then = std::chrono::system_clock::now() - std::chrono::duration<double>(age_s);
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(then.time_since_epoch()).count();
    const timespec times[2] = {{ns / 1'000'000'000, ns % 1'000'000'000}, {ns / 1'000'000'000, ns % 1'000'000'000}};
    ASSERT_EQ(utimensat(AT_FDCWD, path.c_str(), times, 0), 0);
}

/// How long ago `path` was last modified.
inline double file_age_s(const std::string& path) {
    return std::chrono::duration<double>(std::filesystem::file_time_type::clock::now() -
                                         std::filesystem::last_write_time(path))
        .count();
}

}  // namespace steadylight::testing
