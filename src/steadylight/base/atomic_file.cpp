#include "steadylight/base/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <utility>

#include "steadylight/base/error.h"

namespace steadylight {
namespace {

std::atomic<WrittenFiles*> g_written_files{nullptr};

/// A file descriptor, closed when it goes.
class Descriptor {
public:
    explicit Descriptor(int fd) : m_fd(fd) {}
    ~Descriptor() {
        if (m_fd >= 0) ::close(m_fd);
    }
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    int get() const { return m_fd; }
    /// Closes it; false (errno set) when closing failed, where a full disk may show.
    bool close() { return ::close(std::exchange(m_fd, -1)) == 0; }

private:
    int m_fd;
};

/// Creates `path` anew: never through a symbolic link, never onto a file that is there.
Descriptor create_new_file(const std::string& path) {
    if (::unlink(path.c_str()) != 0 && errno != ENOENT) throw std::runtime_error(std::strerror(errno));
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0) throw std::runtime_error(std::strerror(errno));
    return Descriptor(fd);
}

/// A name that opens the file `fd` was opened on, whatever now stands at `path`.
std::string name_of(const Descriptor& fd, const std::string& path) {
    const std::string by_descriptor = "/proc/self/fd/" + std::to_string(fd.get());
    return ::access(by_descriptor.c_str(), W_OK) == 0 ? by_descriptor : path;
}

void write_bytes(const std::string& path, const char* data, size_t size) {
    write_file_atomically(path, [&](const std::string& file) {
        std::ofstream out(file, std::ios::binary);
        out.write(data, std::streamsize(size));
        out.close();
        if (!out) throw std::runtime_error(std::strerror(errno));
    });
}

}  // namespace

WrittenFiles::WrittenFiles() { g_written_files.store(this); }
WrittenFiles::~WrittenFiles() { g_written_files.store(nullptr); }

std::vector<std::string> WrittenFiles::paths() const {
    const std::lock_guard lock(m_mutex);
    return m_paths;
}

void WrittenFiles::add(const std::string& path) {
    const std::lock_guard lock(m_mutex);
    m_paths.push_back(path);
}

void write_new_file(const std::string& path, const std::string& text) {
    Descriptor fd = create_new_file(path);
    for (size_t written = 0; written < text.size();) {
        const ssize_t n = ::write(fd.get(), text.data() + written, text.size() - written);
        if (n < 0 && errno != EINTR) throw std::runtime_error(std::strerror(errno));
        if (n > 0) written += size_t(n);
    }
    if (!fd.close()) throw std::runtime_error(std::strerror(errno));
}

void write_file_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
    const std::string temporary = path + ".partial";
    try {
        std::error_code error;
        if (std::filesystem::is_symlink(path, error))
            throw std::runtime_error(
                "it is a symbolic link; files are written into the output folder, not through links");
        {
            const Descriptor fd = create_new_file(temporary);
            write(name_of(fd, temporary));
        }
        std::filesystem::rename(temporary, path);
        if (WrittenFiles* written = g_written_files.load()) written->add(path);
    } catch (const std::exception& e) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        if (std::filesystem::is_directory(path, ignored)) throw OutputError(path, "it is a folder");
        throw OutputError(path, e.what());
    }
}

void create_output_folder(const std::string& dir, const std::string& option) {
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error) throw InputError(option, dir + ": cannot create the folder: " + error.message());
    // A file written and removed: a read-only folder or file system shows here, not after hours.
    // Named per process: renders of one folder on a farm start together.
    const std::string probe =
        (std::filesystem::path(dir) / (".steadylight-write-test-" + std::to_string(getpid()))).string();
    try {
        write_new_file(probe, "ok");
    } catch (const std::exception& e) {
        throw InputError(option, dir + ": cannot write into the folder: " + e.what());
    }
    std::filesystem::remove(probe, error);
}

void write_text_file(const std::string& path, const std::string& text) { write_bytes(path, text.data(), text.size()); }

void write_binary_file(const std::string& path, const std::vector<unsigned char>& bytes) {
    write_bytes(path, reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

}  // namespace steadylight
