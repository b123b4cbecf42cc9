#include "steadylight/output/atomic_file.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace steadylight {

void write_file_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
    const std::string temporary = path + ".partial";
    try {
        write(temporary);
        std::filesystem::rename(temporary, path);
    } catch (const std::exception& e) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw std::runtime_error("cannot write " + path + ": " + e.what());
    }
}

void write_text_file(const std::string& path, const std::string& text) {
    write_file_atomically(path, [&](const std::string& file) {
        std::ofstream out(file, std::ios::binary);
        out << text;
        out.close();
        if (!out) throw std::runtime_error("write failed");
    });
}

}  // namespace steadylight
