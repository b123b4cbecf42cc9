// Claiming frames in a shared output folder (frame_claim.h).
#include "steadylight/run/frame_claim.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "steadylight/base/atomic_file.h"
#include "steadylight/base/error.h"
#include "steadylight/base/file_lock.h"
#include "steadylight/output/frame_names.h"
#include "steadylight/run/settings_file.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

std::string host_name() {
    char name[256] = {};
    ::gethostname(name, sizeof name - 1);
    return name;
}

bool process_alive(int pid) { return pid > 0 && (::kill(pid, 0) == 0 || errno == EPERM); }

/// The modification time of `path` in seconds by the file system's clock; nullopt when missing.
std::optional<double> modified_s(const std::string& path) {
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0) return std::nullopt;
    return double(status.st_mtim.tv_sec) + 1e-9 * double(status.st_mtim.tv_nsec);
}

/// Sets the modification time of `path` to now by the file system's clock (on NFS the server
/// sets it), so that claim ages never compare two machines' clocks.
bool touch(const std::string& path) { return ::utimensat(AT_FDCWD, path.c_str(), nullptr, 0) == 0; }

/// The file system's "now", read back from `path` after touching it.
double file_system_now_s(const std::string& path) {
    if (!touch(path)) throw std::runtime_error("cannot touch " + path + ": " + std::strerror(errno));
    return modified_s(path).value_or(0);
}

struct ClaimFile {
    std::string host;
    int pid = 0;
};

std::optional<ClaimFile> read_claim(const std::string& path) {
    std::ifstream in(path);
    if (!in) return std::nullopt;
    try {
        const nlohmann::json json = nlohmann::json::parse(in);
        const nlohmann::json& pid = json.at("pid");
        if (!pid.is_number_integer() || pid.get<int64_t>() != int64_t(pid.get<int>())) return std::nullopt;
        return ClaimFile{json.at("host").get<std::string>(), pid.get<int>()};
    } catch (const nlohmann::json::exception&) {
        return std::nullopt;
    }
}

bool is_mine(const std::optional<ClaimFile>& claim) {
    return claim && claim->host == host_name() && claim->pid == ::getpid();
}

/// Writes this process's claim to `path`: created only if absent (link(2) is atomic, also on
/// NFS) unless `replace`. False when it exists already.
bool write_claim(const std::string& path, bool replace) {
    const nlohmann::json json = {{"host", host_name()},
                                 {"pid", ::getpid()},
                                 {"time", fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(std::time(nullptr)))}};
    const std::string temporary = fmt::format("{}.{}-{}.tmp", path, host_name(), ::getpid());
    try {
        write_new_file(temporary, json.dump() + "\n");
    } catch (const std::exception& e) {
        throw OutputError(temporary, e.what());
    }
    std::error_code ignored;
    if (replace) {
        fs::rename(temporary, path);
        return true;
    }
    const int result = ::link(temporary.c_str(), path.c_str());
    const int error = errno;
    fs::remove(temporary, ignored);
    if (result == 0) return true;
    if (error == EEXIST) return false;
    throw std::runtime_error("cannot create the claim " + path + ": " + std::strerror(error));
}

/// Why a claim is dead and may be taken over, or "" when it stands.
std::string dead_claim_reason(const std::optional<ClaimFile>& holder, double age_s, double stale_s) {
    if (holder && holder->host == host_name() && !process_alive(holder->pid))
        return fmt::format("its process {} on this host is gone", holder->pid);
    if (age_s > stale_s) return fmt::format("not refreshed for {:.0f} s, the limit is {:.0f} s", age_s, stale_s);
    return "";
}

std::string describe_holder(const std::optional<ClaimFile>& holder, double age_s) {
    if (!holder) return fmt::format("an unreadable claim, refreshed {:.0f} s ago", age_s);
    return fmt::format("host {}, pid {}, refreshed {:.0f} s ago", holder->host, holder->pid, age_s);
}

/// Removes the frame's `.partial` files: left by a process that died inside the frame.
void remove_stale_partials(const std::string& out_dir, const std::string& scene_name, int frame) {
    const std::string prefix = fs::path(frame_file_name(out_dir, scene_name, frame, "")).filename().string();
    for (const fs::directory_entry& entry : fs::directory_iterator(out_dir)) {
        const std::string name = entry.path().filename().string();
        if (name.starts_with(prefix) && name.ends_with(".partial")) {
            std::error_code ignored;
            if (fs::remove(entry.path(), ignored)) spdlog::info("frame {}: removed the stale {}", frame, name);
        }
    }
}

}  // namespace

std::string frame_claim_name(const std::string& out_dir, const std::string& scene_name, int frame) {
    return frame_file_name(out_dir, scene_name, frame, "claim");
}

struct FrameClaim::Refresher {
    std::mutex mutex;
    std::condition_variable wake;
    bool stop = false;
    std::thread thread;
};

FrameClaim::FrameClaim(std::string path, double refresh_s)
    : m_path(std::move(path)), m_refresher(std::make_unique<Refresher>()) {
    m_refresher->thread = std::thread([this, refresh = std::chrono::duration<double>(refresh_s)] {
        std::unique_lock lock(m_refresher->mutex);
        while (!m_refresher->wake.wait_for(lock, refresh, [this] { return m_refresher->stop; }))
            if (!touch(m_path)) spdlog::warn("cannot refresh the claim {}: {}", m_path, std::strerror(errno));
    });
}

FrameClaim::~FrameClaim() {
    {
        const std::lock_guard lock(m_refresher->mutex);
        m_refresher->stop = true;
    }
    m_refresher->wake.notify_all();
    m_refresher->thread.join();
    try {
        // Remove it only while it is still ours: a process that judged it dead may hold it now.
        const FileLock lock(folder_lock_name(fs::path(m_path).parent_path().string()));
        if (is_mine(read_claim(m_path))) fs::remove(m_path);
    } catch (const std::exception& e) {
        spdlog::warn("cannot remove the claim {}: {}", m_path, e.what());
    }
}

ClaimAttempt try_claim_frame(const std::string& out_dir, const std::string& scene_name, int frame, double stale_s,
                             double refresh_s) {
    const std::string path = frame_claim_name(out_dir, scene_name, frame);
    const std::string lock_path = folder_lock_name(out_dir);
    const FileLock lock(lock_path);
    ClaimAttempt attempt;
    if (!write_claim(path, false)) {
        const double age_s =
            file_system_now_s(lock_path) - modified_s(path).value_or(-std::numeric_limits<double>::infinity());
        const std::optional<ClaimFile> holder = read_claim(path);
        const std::string why = dead_claim_reason(holder, age_s, stale_s);
        if (why.empty()) {
            attempt.holder = describe_holder(holder, age_s);
            return attempt;
        }
        attempt.taken_over = describe_holder(holder, age_s) + ": " + why;
        write_claim(path, true);
        // Its holder may have died inside the frame. (A process that fails or is interrupted
        // removes its own temporary files; only one killed outright leaves them, and its claim.)
        remove_stale_partials(out_dir, scene_name, frame);
    }
    attempt.claim = std::make_unique<FrameClaim>(path, refresh_s);
    return attempt;
}

}  // namespace steadylight
