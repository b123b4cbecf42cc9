// Frame manifests: writing them last, and checking a frame's files against them (frame_manifest.h).
#include "steadylight/run/frame_manifest.h"

#include <filesystem>
#include <fstream>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "steadylight/base/atomic_file.h"
#include "steadylight/base/hash.h"
#include "steadylight/output/frame_names.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

/// Checksum of a whole file as 16 hex digits; nullopt when it cannot be read. Read in large
/// blocks, to its end whatever its size said: a production frame's EXR is megabytes, which a
/// character at a time takes several times longer to read than to checksum.
std::optional<std::string> file_checksum(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::string bytes;
    std::error_code error;
    const uintmax_t size = fs::file_size(path, error);
    if (!error) bytes.reserve(size_t(size));
    std::vector<char> block(size_t(1) << 20);
    while (in.read(block.data(), std::streamsize(block.size())) || in.gcount() > 0)
        bytes.append(block.data(), size_t(in.gcount()));
    if (in.bad()) return std::nullopt;
    return fmt::format("{:016x}", checksum64(bytes.data(), bytes.size()));
}

/// Why the file a manifest entry names is not as written, or "" when it is.
std::string check_entry(const fs::path& out_dir, const nlohmann::json& entry) {
    const std::string name = entry.at("name").get<std::string>();
    // Only files of the folder: a damaged manifest must not send the check to /dev/zero.
    const fs::path relative = fs::path(name).lexically_normal();
    if (name.empty() || relative.is_absolute() || *relative.begin() == "..")
        return "its manifest names \"" + name + "\"";
    const fs::path path = out_dir / relative;
    std::error_code error;
    if (!fs::is_regular_file(path, error)) return name + " is missing";
    const uintmax_t bytes = fs::file_size(path, error);
    if (error) return name + " is missing";
    // A count too large for an integer is read as a float, which must not be converted (a fuzzing finding).
    const nlohmann::json& written = entry.at("bytes");
    if (!written.is_number_unsigned()) return "its manifest gives " + name + " no byte count";
    if (bytes != written.get<uintmax_t>())
        return fmt::format("{} has {} bytes, {} were written", name, bytes, written.get<uintmax_t>());
    if (file_checksum(path) != entry.at("checksum").get<std::string>())
        return name + " has changed since it was written";
    return "";
}

}  // namespace

std::string frame_manifest_name(const std::string& out_dir, const std::string& scene_name, int frame) {
    return frame_file_name(out_dir, scene_name, frame, "manifest.json");
}

void write_frame_manifest(const std::string& out_dir, const std::string& scene_name, int frame,
                          const std::vector<std::string>& files, const std::string& settings_key) {
    nlohmann::json entries = nlohmann::json::array();
    for (const std::string& file : files) {
        const std::optional<std::string> checksum = file_checksum(file);
        if (!checksum) throw std::runtime_error("cannot read back " + file);
        entries.push_back({{"name", fs::path(file).lexically_relative(out_dir).generic_string()},
                           {"bytes", fs::file_size(file)},
                           {"checksum", *checksum}});
    }
    const nlohmann::json manifest = {{"frame", frame}, {"settings_key", settings_key}, {"files", entries}};
    write_text_file(frame_manifest_name(out_dir, scene_name, frame), manifest.dump(2) + "\n");
}

FrameCheck check_frame_outputs(const std::string& out_dir, const std::string& scene_name, int frame,
                               const std::string& settings_key) {
    const std::string name = frame_manifest_name(out_dir, scene_name, frame);
    std::ifstream in(name);
    if (!in) return {false, ""};
    try {
        const nlohmann::json manifest = nlohmann::json::parse(in);
        if (manifest.at("settings_key").get<std::string>() != settings_key)
            return {false, "it was rendered with other settings"};
        if (manifest.at("files").empty()) return {false, "its manifest lists no files"};
        for (const nlohmann::json& entry : manifest.at("files"))
            if (std::string problem = check_entry(out_dir, entry); !problem.empty()) return {false, problem};
    } catch (const nlohmann::json::exception& e) {
        return {false, fs::path(name).filename().string() + " is damaged (" + e.what() + ")"};
    }
    return {true, ""};
}

}  // namespace steadylight
