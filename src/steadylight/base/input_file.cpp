#include "steadylight/base/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "steadylight/base/error.h"

namespace steadylight {
namespace {

/// What a file that is not a regular one is, for the message.
const char* kind_of(mode_t mode) {
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

}  // namespace

InputFolder InputFolder::of_scene(const std::string& scene_file) {
    std::error_code error;
    const std::filesystem::path folder = std::filesystem::absolute(scene_file).parent_path();
    InputFolder inputs;
    inputs.m_folder = std::filesystem::weakly_canonical(folder, error).string();
    if (error || inputs.m_folder.empty()) throw InputError(scene_file, "cannot resolve its folder: " + error.message());
    return inputs;
}

void InputFolder::check(const std::string& path) const {
    if (m_folder.empty()) return;
    std::error_code error;
    const std::filesystem::path resolved = std::filesystem::weakly_canonical(path, error);
    const std::filesystem::path relative = resolved.lexically_relative(m_folder);
    if (error || relative.empty() || *relative.begin() == "..")
        throw InputError(path, "lies outside the scene file's folder " + m_folder +
                                   (resolved.string() != path ? " (it resolves to " + resolved.string() + ")" : "") +
                                   ", and --confine-inputs allows only files inside it");
}

std::string read_input_file(const std::string& path, const InputFolder& inputs) {
    inputs.check(path);
    // O_NONBLOCK: opening a FIFO with no writer would otherwise wait for one.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        throw InputError(path,
                         std::string("cannot open: ") + (errno == ENOENT || errno == ENAMETOOLONG || errno == ENOTDIR
                                                             ? "file not found"
                                                             : std::strerror(errno)));
    struct stat status {};
    std::string bytes;
    std::string problem;
    if (::fstat(fd, &status) != 0) {
        problem = std::string("cannot read: ") + std::strerror(errno);
    } else if (!S_ISREG(status.st_mode)) {
        problem = std::string("not a regular file: it is ") + kind_of(status.st_mode) + ", which is not read";
    } else if (size_t(status.st_size) > max_input_file_bytes) {
        problem = "larger than 2 GB, the most a scene's file may be";
    } else {
        bytes.resize(size_t(status.st_size));
        size_t done = 0;
        while (done < bytes.size()) {
            const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) {
                problem = n < 0 ? std::string("cannot read: ") + std::strerror(errno) : "truncated while being read";
                break;
            }
            done += size_t(n);
        }
    }
    ::close(fd);
    if (!problem.empty()) throw InputError(path, problem);
    return bytes;
}

}  // namespace steadylight
