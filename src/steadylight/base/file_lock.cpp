// flock(2) on a lock file (file_lock.h).
#include "steadylight/base/file_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "steadylight/base/error.h"

namespace steadylight {

FileLock::FileLock(const std::string& path) : m_path(path) {
    m_fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0666);
    // Not through a symbolic link (atomic_file.h): a link put there by someone else fails here.
    if (m_fd < 0)
        throw OutputError(path, std::string("cannot open it as a lock file: ") + std::strerror(errno) +
                                    (errno == ELOOP ? " (it is a symbolic link)" : ""));
    int result = 0;
    while ((result = ::flock(m_fd, LOCK_EX)) != 0 && errno == EINTR) {
    }
    if (result != 0) {
        const int error = errno;
        ::close(m_fd);
        throw std::runtime_error("cannot lock " + path + ": " + std::strerror(error) +
                                 " (does the file system support flock? see docs/farm.md)");
    }
}

FileLock::~FileLock() {
    // Closing the descriptor releases the lock.
    ::close(m_fd);
}

}  // namespace steadylight
