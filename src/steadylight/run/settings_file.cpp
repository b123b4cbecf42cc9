// The settings file beside the frames: making it, and refusing other settings (settings_file.h).
#include "steadylight/run/settings_file.h"

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "steadylight/base/atomic_file.h"
#include "steadylight/base/error.h"
#include "steadylight/base/hash.h"
#include "steadylight/base/lock_file.h"
#include "steadylight/run/frame_selection.h"
#include "steadylight/scene/scene_desc.h"

namespace steadylight {
namespace {

std::string hex_checksum(const std::string& bytes) {
    return fmt::format("{:016x}", checksum64(bytes.data(), bytes.size()));
}

std::string file_checksum(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, "cannot open");
    return hex_checksum(std::string{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()});
}

std::string utc_now() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

/// The format version of a settings file's "render" part: 1 for files from before versions, 0
/// when it is not a number.
int format_of(const nlohmann::json& render) {
    if (!render.is_object()) return 0;
    const nlohmann::json version = render.value("format_version", nlohmann::json(1));
    return version.is_number_integer() ? version.get<int>() : 0;
}

/// The frames a settings file lists; nullopt when the list is damaged (not a string, not a frame
/// list, or more frames than a scene may have).
std::optional<std::vector<int>> frames_of(const nlohmann::json& json) {
    const auto frames = json.find("frames");
    if (frames == json.end()) return std::vector<int>{};
    if (!frames->is_string()) return std::nullopt;
    const std::string& text = frames->get_ref<const std::string&>();
    if (text.empty()) return std::vector<int>{};
    try {
        const FrameSelection selection = parse_frame_selection(text);
        int64_t listed = 0;
        for (const FrameSpan& span : selection.spans) listed += (int64_t(span.last) - span.first) / span.step + 1;
        if (listed > max_frame_count) return std::nullopt;
        return select_frames(selection, max_frame_count);
    } catch (const InputError&) {
        return std::nullopt;
    }
}

/// "/render/method: \"photon\" -> \"localized\"; ..." for the differences of two "render" parts.
std::string describe_differences(const nlohmann::json& before, const nlohmann::json& now) {
    std::string text;
    for (const nlohmann::json& change : nlohmann::json::diff(before, now)) {
        const nlohmann::json::json_pointer where(change.at("path").get<std::string>());
        const std::string old_value = before.contains(where) ? before.at(where).dump() : "(none)";
        const std::string new_value = now.contains(where) ? now.at(where).dump() : "(none)";
        text += fmt::format("{}{}: {} -> {}", text.empty() ? "" : "; ", where.to_string(), old_value, new_value);
    }
    return text;
}

}  // namespace

nlohmann::json make_settings_json(const RenderSettings& settings, const RunInfo& run) {
    nlohmann::json render = {{"format_version", settings_format_version},
                             {"scene", {{"name", run.scene_name}, {"checksum", file_checksum(settings.scene_file)}}},
                             {"method", method_info(settings.method).name},
                             {"size", {run.width, run.height}},
                             {"aov_pngs", settings.aov_pngs},
                             {"output", settings.output}};
    render.update(method_settings_json(settings));
    return {{"steadylight_version", STEADYLIGHT_VERSION}, {"date", utc_now()},      {"scene_file", settings.scene_file},
            {"frames", format_frame_list(run.frames)},    {"threads", run.threads}, {"cache_file", settings.cache_file},
            {"video", settings.output.video_file},        {"render", render}};
}

std::string settings_key(const nlohmann::json& settings_json) {
    return hex_checksum(settings_json.at("render").dump());
}

std::string folder_lock_name(const std::string& out_dir) {
    return (std::filesystem::path(out_dir) / ".steadylight.lock").string();
}

std::string settings_file_name(const std::string& out_dir, const std::string& scene_name) {
    return (std::filesystem::path(out_dir) / (scene_name + ".settings.json")).string();
}

void write_settings_file(const std::string& path, nlohmann::json settings_json, bool overwrite) {
    // Many processes may start at once on one folder: check and write under its lock.
    const std::unique_ptr<LockFile> lock =
        LockFile::lock(folder_lock_name(std::filesystem::path(path).parent_path().string()), "the settings file");
    if (std::ifstream in(path); in) {
        nlohmann::json before;
        try {
            before = nlohmann::json::parse(in);
        } catch (const nlohmann::json::exception&) {
            spdlog::warn("{}: damaged; it is replaced", path);
        }
        if (before.contains("render") && before["render"] != settings_json["render"]) {
            const std::string differences = format_of(before["render"]) != settings_format_version
                                                ? fmt::format(
                                                      "settings file format {}, this steadylight writes "
                                                      "format {}",
                                                      format_of(before["render"]), settings_format_version)
                                                : describe_differences(before["render"], settings_json["render"]);
            if (!overwrite)
                throw InputError(path, "the frames in this folder were rendered with other settings (" + differences +
                                           "); use the same settings, another --out, or --overwrite to render the "
                                           "selected frames again");
            spdlog::warn("{}: settings changed ({}); --overwrite renders the selected frames again", path, differences);
        } else if (before.contains("render")) {
            // Same settings: the file lists the frames of every run.
            std::optional<std::vector<int>> frames = frames_of(before);
            if (!frames) {
                spdlog::warn("{}: its list of frames is damaged; it lists this run's frames only", path);
                frames.emplace();
            }
            const std::vector<int> now = frames_of(settings_json).value();
            frames->insert(frames->end(), now.begin(), now.end());
            std::sort(frames->begin(), frames->end());
            frames->erase(std::unique(frames->begin(), frames->end()), frames->end());
            settings_json["frames"] = format_frame_list(*frames);
        }
    }
    write_text_file(path, settings_json.dump(2) + "\n");
}

}  // namespace steadylight
