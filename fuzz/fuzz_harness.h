// What the fuzz harnesses (fuzz/*_fuzz.cpp) share. Each harness defines LLVMFuzzerTestOneInput:
// built with libFuzzer by scripts/fuzz.sh, and with replay_main.cpp into the test suite, which
// runs the repository's seeds and the inputs of past findings (fuzz/regressions/) through it.
//
// The loaders read paths, so a harness writes its input into a folder of this process (on
// /dev/shm where there is one), which holds links to the entries of $STEADYLIGHT_FUZZ_FILES when
// that is set, so that relative references (a scene's meshes, a glTF's buffers and images, a
// manifest's frame files) resolve. A harness lets steadylight's InputError pass (the clear message
// a user sees) and nothing else: any other exception, a sanitizer report, a crash, an input
// taking more than a second or an allocation over 2 GB is a finding.
#pragma once

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "steadylight/base/error.h"

namespace steadylight::fuzz {

namespace fs = std::filesystem;

/// The folder of this process, made at first use and removed at exit.
class HarnessFolder {
public:
    HarnessFolder() {
        spdlog::set_level(spdlog::level::off);  // loaders' warnings would cost more than the parsing
        const fs::path base = fs::is_directory("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
        m_path = base / ("steadylight_fuzz_" + std::to_string(::getpid()));
        fs::remove_all(m_path);
        fs::create_directories(m_path);
        if (const char* files = std::getenv("STEADYLIGHT_FUZZ_FILES"); files && *files)
            for (const fs::directory_entry& entry : fs::directory_iterator(files))
                fs::create_symlink(fs::absolute(entry.path()), m_path / entry.path().filename());
    }
    ~HarnessFolder() {
        std::error_code ignored;
        fs::remove_all(m_path, ignored);
    }
    const fs::path& path() const { return m_path; }

private:
    fs::path m_path;
};

inline const fs::path& folder() {
    static const HarnessFolder harness_folder;
    return harness_folder.path();
}

/// Writes the input as `name` in the folder and returns its path.
inline std::string write_input(const uint8_t* data, size_t size, const std::string& name) {
    const fs::path path = folder() / name;
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), std::streamsize(size));
    return path.string();
}

/// Runs `call`, letting an InputError (a clear message about bad input) pass.
template <class Call>
void expect_clear_errors(Call&& call) {
    try {
        call();
    } catch (const InputError&) {
    }
}

}  // namespace steadylight::fuzz
