#include "steadylight/base/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "steadylight/base/error.h"

namespace steadylight {
namespace {

std::atomic<WrittenFiles*> g_written_files{nullptr};

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

void write_file_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
    const std::string temporary = path + ".partial";
    try {
        write(temporary);
        std::filesystem::rename(temporary, path);
        if (WrittenFiles* written = g_written_files.load()) written->add(path);
    } catch (const std::exception& e) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        if (std::filesystem::is_directory(path, ignored)) throw OutputError(path, "it is a folder");
        throw OutputError(path, e.what());
    }
}

namespace {

void write_bytes(const std::string& path, const char* data, size_t size) {
    write_file_atomically(path, [&](const std::string& file) {
        std::ofstream out(file, std::ios::binary);
        out.write(data, std::streamsize(size));
        out.close();
        if (!out) throw std::runtime_error(std::strerror(errno));
    });
}

}  // namespace

void create_output_folder(const std::string& dir, const std::string& option) {
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error) throw InputError(option, dir + ": cannot create the folder: " + error.message());
    // A file written and removed: a read-only folder or file system shows here, not after hours.
    // Named per process: renders of one folder on a farm start together.
    const std::string probe =
        (std::filesystem::path(dir) / (".steadylight-write-test-" + std::to_string(getpid()))).string();
    if (std::ofstream out(probe); !(out << "ok" && (out.close(), out)))
        throw InputError(option, dir + ": cannot write into the folder: " + std::strerror(errno));
    std::filesystem::remove(probe, error);
}

void write_text_file(const std::string& path, const std::string& text) { write_bytes(path, text.data(), text.size()); }

void write_binary_file(const std::string& path, const std::vector<unsigned char>& bytes) {
    write_bytes(path, reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

}  // namespace steadylight
