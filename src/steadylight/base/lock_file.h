// Lock files that hold across machines. Several processes, on one machine or many, write one
// output folder: the settings file is checked and written by one at a time, a segment's static
// cache is computed by one while the others wait and then load it, and each frame is rendered by
// the process that claimed it (run/frame_claim.h). flock(2) cannot carry this: network and FUSE
// file systems may keep such locks per client (through two sshfs mounts of one folder, two
// exclusive flocks both succeed at once). What every shared file system does make atomic is
// link(2) and rename(2), so a lock here is a file:
//   - taken by writing `<lock>.<host>-<pid>.tmp` (host, pid, a random token, the time, as JSON)
//     and link(2)ing it to `<lock>`, which fails when the file exists;
//   - refreshed every refresh_s while held, by rewriting its first byte (the file server sets the
//     modification time on a write);
//   - taken over when dead: its host is this host and its process is gone, or it was not
//     refreshed for stale_s. The age is judged by the file system's clock (the temporary file
//     just written, against the lock's modification time), so machines' clocks never meet.
//     A lock file left empty by steadylight's older flock locks is dead at once;
//   - taken over, and released (removed only while its token is still ours), while holding
//     `<lock>.break`, itself made by link(2): whoever takes a dead lock over looks again under the
//     break, so two processes that both found it dead cannot both take it. A break file is held
//     for a few file operations; one left by a process killed in between is dead by the same
//     rules.
// Nothing is read or written through a symbolic link (base/atomic_file.h). The file system must
// give close-to-open consistency: see docs/farm.md, "The shared output folder".
#pragma once

#include <memory>
#include <string>

namespace steadylight {

/// How often a holder refreshes its lock file, and after how long without a refresh others take
/// it over. The stale time must exceed the refresh time plus the longest time a client of the
/// shared file system caches a file's attributes (docs/farm.md).
struct LockTimes {
    double refresh_s = 10;
    double stale_s = 120;
};

/// The defaults, or for tests the value of STEADYLIGHT_TEST_LOCK_TIMES, "REFRESH_S,STALE_S" (so
/// that a test sees a dead lock taken over in seconds). Throws std::runtime_error when that value
/// is malformed.
LockTimes lock_times();

class LockFile;

/// What LockFile::try_lock found.
struct LockAttempt {
    std::unique_ptr<LockFile> lock;  // set when this process now holds it
    std::string holder;              // else who does: "host vm, pid 123, refreshed 4 s ago"
    std::string taken_over;          // when a dead lock was taken over: whose and why
};

/// A lock this process holds; refreshed by a thread of its own while it lives, and removed (when
/// still this process's) when it goes away.
class LockFile {
public:
    /// \brief Takes the lock `path` when it is free or dead; never waits. Throws OutputError naming
    /// the file when it cannot be written, or when `path` is not a regular file (a symbolic link).
    static LockAttempt try_lock(const std::string& path, const LockTimes& times = lock_times());

    /// \brief Waits until this process holds the lock `path`; logs once what it waits for
    /// (`what`, such as "the settings file") and who holds it. Throws as try_lock does.
    static std::unique_ptr<LockFile> lock(const std::string& path, const std::string& what,
                                          const LockTimes& times = lock_times());

    ~LockFile();
    LockFile(const LockFile&) = delete;
    LockFile& operator=(const LockFile&) = delete;

    const std::string& path() const { return m_path; }

private:
    struct Refresher;
    LockFile(std::string path, std::string token, const LockTimes& times);

    std::string m_path;
    std::string m_token;
    LockTimes m_times;
    std::unique_ptr<Refresher> m_refresher;
};

}  // namespace steadylight
