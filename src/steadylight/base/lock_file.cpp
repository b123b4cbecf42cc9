// Lock files made with link(2), refreshed, taken over when dead (lock_file.h).
#include "steadylight/base/lock_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <mutex>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "steadylight/base/atomic_file.h"
#include "steadylight/base/error.h"
#include "steadylight/base/stopwatch.h"

namespace steadylight {
namespace {

std::string host_name() {
    char name[256] = {};
    ::gethostname(name, sizeof name - 1);
    return name;
}

bool process_alive(int pid) { return pid > 0 && (::kill(pid, 0) == 0 || errno == EPERM); }

double seconds_of(const timespec& time) { return double(time.tv_sec) + 1e-9 * double(time.tv_nsec); }

void pause_for(double seconds) { std::this_thread::sleep_for(std::chrono::duration<double>(seconds)); }

/// Who wrote a lock file.
struct Holder {
    std::string host;
    int pid = 0;
    std::string token;  // tells this process's lock from an earlier process's of the same pid
};

/// What is at a lock's path.
struct Observed {
    bool exists = false;
    bool empty = false;            // an older steadylight's flock file
    std::optional<Holder> holder;  // nullopt when unreadable
    double modified_s = 0;         // by the file system's clock
};

std::optional<Holder> parse_holder(const std::string& text) {
    try {
        const nlohmann::json json = nlohmann::json::parse(text);
        const nlohmann::json& pid = json.at("pid");
        if (!pid.is_number_integer() || pid.get<int64_t>() != int64_t(pid.get<int>())) return std::nullopt;
        return Holder{json.at("host").get<std::string>(), pid.get<int>(), json.value("token", "")};
    } catch (const nlohmann::json::exception&) {
        return std::nullopt;
    }
}

/// Reads the lock file at `path` without following a symbolic link or blocking on a FIFO.
Observed observe(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        if (errno == ENOENT) return {};
        throw OutputError(path, std::string("cannot open it as a lock file: ") + std::strerror(errno) +
                                    (errno == ELOOP ? " (it is a symbolic link)" : ""));
    }
    struct stat status {};
    std::string text(4096, '\0');
    const bool regular = ::fstat(fd, &status) == 0 && S_ISREG(status.st_mode);
    const ssize_t size = regular ? ::read(fd, text.data(), text.size()) : 0;
    ::close(fd);
    if (!regular) throw OutputError(path, "cannot open it as a lock file: it is not a regular file");
    text.resize(size_t(std::max<ssize_t>(size, 0)));
    return {true, status.st_size == 0, parse_holder(text), seconds_of(status.st_mtim)};
}

/// Why a lock is dead and may be taken over, or "" while it stands.
std::string dead_reason(const Observed& lock, double age_s, double stale_s) {
    if (lock.empty) return "an empty lock file, left by an older steadylight";
    if (lock.holder && lock.holder->host == host_name() && !process_alive(lock.holder->pid))
        return fmt::format("its process {} on this host is gone", lock.holder->pid);
    if (age_s > stale_s) return fmt::format("not refreshed for {:.0f} s, the limit is {:.0f} s", age_s, stale_s);
    return "";
}

std::string describe(const Observed& lock, double age_s) {
    if (!lock.holder) return fmt::format("an unreadable lock file, refreshed {:.0f} s ago", age_s);
    return fmt::format("host {}, pid {}, refreshed {:.0f} s ago", lock.holder->host, lock.holder->pid, age_s);
}

std::string random_token() {
    std::random_device device;
    return fmt::format("{:08x}{:08x}", device(), device());
}

/// This process's lock content in `<lock>.<host>-<pid>.tmp`, to be linked or renamed onto the
/// lock; removed when it goes away. Its modification time is the file system's "now".
class TemporaryLockFile {
public:
    TemporaryLockFile(const std::string& lock_path, const std::string& token)
        : m_path(fmt::format("{}.{}-{}.tmp", lock_path, host_name(), ::getpid())) {
        const nlohmann::json json = {{"host", host_name()},
                                     {"pid", ::getpid()},
                                     {"token", token},
                                     {"time", fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(std::time(nullptr)))}};
        try {
            write_new_file(m_path, json.dump() + "\n");
        } catch (const std::exception& e) {
            throw OutputError(m_path, e.what());
        }
        struct stat status {};
        if (::stat(m_path.c_str(), &status) != 0) throw OutputError(m_path, std::strerror(errno));
        m_written_s = seconds_of(status.st_mtim);
    }
    ~TemporaryLockFile() { ::unlink(m_path.c_str()); }
    TemporaryLockFile(const TemporaryLockFile&) = delete;
    TemporaryLockFile& operator=(const TemporaryLockFile&) = delete;

    /// How long before this file was written `lock` was last refreshed.
    double age_s(const Observed& lock) const { return m_written_s - lock.modified_s; }

    /// Creates `lock` as a link to this file; false when it exists.
    bool link_to(const std::string& lock) const {
        if (::link(m_path.c_str(), lock.c_str()) == 0) return true;
        const int error = errno;
        // sshfs answers EPERM when another client made the file: SFTP has no code for "exists".
        if (error == EEXIST || observe(lock).exists) return false;
        throw OutputError(lock, std::string("cannot create the lock file: ") + std::strerror(error) +
                                    " (the folder's file system must support hard links: see docs/farm.md)");
    }

    /// Puts this file in place of `lock`, whatever is there.
    void rename_onto(const std::string& lock) const {
        if (::rename(m_path.c_str(), lock.c_str()) != 0)
            throw OutputError(lock, std::string("cannot replace the dead lock file: ") + std::strerror(errno));
    }

private:
    std::string m_path;
    double m_written_s = 0;
};

/// `<lock>.break`, held while a lock is taken over or released.
class BreakFile {
public:
    /// Holds the break of `lock`, or returns nothing while a live process holds it.
    static std::unique_ptr<BreakFile> try_hold(const std::string& lock, double stale_s) {
        const std::string path = lock + ".break";
        const TemporaryLockFile temporary(path, random_token());
        for (int tries = 0; tries < 2; ++tries) {
            if (temporary.link_to(path)) return std::unique_ptr<BreakFile>(new BreakFile(path));
            const Observed found = observe(path);
            if (found.exists && dead_reason(found, temporary.age_s(found), stale_s).empty()) return nullptr;
            // Left by a process that died between taking and removing it.
            ::unlink(path.c_str());
        }
        return nullptr;
    }

    /// Waits for the break of `lock`: a live holder keeps it for a few file operations, a dead
    /// one's is taken after stale_s.
    static std::unique_ptr<BreakFile> hold(const std::string& lock, double stale_s) {
        const Stopwatch time;
        for (double pause_s = 0.005;; pause_s = std::min(2 * pause_s, 0.1)) {
            if (std::unique_ptr<BreakFile> held = try_hold(lock, stale_s)) return held;
            if (time.elapsed_s() > stale_s + 10)
                throw OutputError(lock + ".break", fmt::format("held by another process for over {:.0f} s", stale_s));
            pause_for(pause_s);
        }
    }

    ~BreakFile() { ::unlink(m_path.c_str()); }
    BreakFile(const BreakFile&) = delete;
    BreakFile& operator=(const BreakFile&) = delete;

private:
    explicit BreakFile(std::string path) : m_path(std::move(path)) {}
    std::string m_path;
};

/// Sets the modification time of `path` by the file system's clock: rewrites its first byte,
/// unchanged (a lock file is JSON, `{...}`), without following a symbolic link.
bool refresh(const std::string& path) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) return false;
    const bool written = ::pwrite(fd, "{", 1, 0) == 1;
    return ::close(fd) == 0 && written;
}

}  // namespace

LockTimes lock_times() {
    const char* value = std::getenv("STEADYLIGHT_TEST_LOCK_TIMES");
    if (!value) return {};
    LockTimes times;
    char comma = 0;
    std::istringstream in(value);
    in >> times.refresh_s >> comma >> times.stale_s;
    if (!in || comma != ',' || !(in >> std::ws).eof() || !std::isfinite(times.stale_s) || !(times.refresh_s > 0) ||
        !(times.stale_s > times.refresh_s))
        throw InputError("STEADYLIGHT_TEST_LOCK_TIMES",
                         fmt::format("\"{}\" is not REFRESH_S,STALE_S with 0 < REFRESH_S < STALE_S", value));
    return times;
}

struct LockFile::Refresher {
    std::mutex mutex;
    std::condition_variable wake;
    bool stop = false;
    std::thread thread;
};

LockFile::LockFile(std::string path, std::string token, const LockTimes& times)
    : m_path(std::move(path)), m_token(std::move(token)), m_times(times), m_refresher(std::make_unique<Refresher>()) {
    m_refresher->thread = std::thread([this, period = std::chrono::duration<double>(times.refresh_s)] {
        std::unique_lock lock(m_refresher->mutex);
        while (!m_refresher->wake.wait_for(lock, period, [this] { return m_refresher->stop; }))
            if (!refresh(m_path)) spdlog::warn("cannot refresh the lock file {}: {}", m_path, std::strerror(errno));
    });
}

LockFile::~LockFile() {
    {
        const std::lock_guard lock(m_refresher->mutex);
        m_refresher->stop = true;
    }
    m_refresher->wake.notify_all();
    m_refresher->thread.join();
    try {
        // Remove it only while it is still ours: a process that judged it dead may hold it now.
        const std::unique_ptr<BreakFile> held = BreakFile::hold(m_path, m_times.stale_s);
        const Observed found = observe(m_path);
        if (found.holder && found.holder->token == m_token) ::unlink(m_path.c_str());
    } catch (const std::exception& e) {
        spdlog::warn("cannot release the lock file {}: {}", m_path, e.what());
    }
}

LockAttempt LockFile::try_lock(const std::string& path, const LockTimes& times) {
    const std::string token = random_token();
    const TemporaryLockFile temporary(path, token);
    LockAttempt attempt;
    for (int tries = 0; tries < 3; ++tries) {
        if (temporary.link_to(path)) {
            attempt.lock.reset(new LockFile(path, token, times));
            return attempt;
        }
        Observed found = observe(path);
        if (!found.exists) continue;  // released meanwhile
        if (dead_reason(found, temporary.age_s(found), times.stale_s).empty()) {
            attempt.holder = describe(found, temporary.age_s(found));
            return attempt;
        }
        // Dead: look again under the break, which one process at a time holds.
        const std::unique_ptr<BreakFile> held = BreakFile::try_hold(path, times.stale_s);
        if (!held) {
            attempt.holder = describe(found, temporary.age_s(found)) + ", being taken over by another process";
            return attempt;
        }
        found = observe(path);
        if (!found.exists) continue;
        const std::string why = dead_reason(found, temporary.age_s(found), times.stale_s);
        if (why.empty()) {
            attempt.holder = describe(found, temporary.age_s(found));
            return attempt;
        }
        temporary.rename_onto(path);
        attempt.taken_over = describe(found, temporary.age_s(found)) + ": " + why;
        attempt.lock.reset(new LockFile(path, token, times));
        return attempt;
    }
    attempt.holder = "processes that take and release it in turn";
    return attempt;
}

std::unique_ptr<LockFile> LockFile::lock(const std::string& path, const std::string& what, const LockTimes& times) {
    const Stopwatch time;
    bool said = false;
    for (double pause_s = 0.01;; pause_s = std::min(2 * pause_s, 1.0)) {
        LockAttempt attempt = try_lock(path, times);
        if (attempt.lock) {
            if (!attempt.taken_over.empty()) spdlog::warn("{}: took over a dead lock ({})", path, attempt.taken_over);
            return std::move(attempt.lock);
        }
        if (!said && time.elapsed_s() > 1) {
            spdlog::info("waiting for {}: {} holds {}", what, attempt.holder, path);
            said = true;
        }
        pause_for(pause_s);
    }
}

}  // namespace steadylight
