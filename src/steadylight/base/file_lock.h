// Advisory locks on a file (flock(2)), held by one process at a time, for an output folder that
// several processes and machines write at once: the settings file is checked or created under
// the folder's lock, and a segment's static cache is computed by one process while the others
// wait and then load it. On a shared file system flock needs the server's lock support (NFSv4,
// Lustre with flock, BeeGFS, CephFS do); see docs/farm.md.
#pragma once

#include <string>

namespace steadylight {

/// \brief An exclusive flock on `path` (created if missing, never removed: removing it would let
/// two processes lock two different files of one name). Blocks until granted; released when the
/// object goes away. Throws std::runtime_error naming `path` when it cannot be opened or locked.
class FileLock {
public:
    explicit FileLock(const std::string& path);
    ~FileLock();
    FileLock(const FileLock&) = delete;
    FileLock& operator=(const FileLock&) = delete;

    const std::string& path() const { return m_path; }

private:
    std::string m_path;
    int m_fd = -1;
};

}  // namespace steadylight
