// The settings a render actually used, written beside its frames as `<out>/<scene>.settings.json`
// (docs/style.md): the scene file, method, image size, every setting of the method, the frames,
// threads, video, steadylight version and date. Its "render" part holds what the images depend
// on — the scene (name and checksum of the scene file), method, size, --aov, the output settings
// (EXR pixel type, exposure, view transform, dither, a transparent background; not --video) and
// the method's settings — and a resumed run must match it: otherwise render_animation() stops
// with an InputError naming the differences (frames from two settings would mix silently),
// unless --overwrite, which renders the selected frames again and replaces the file. Frames,
// threads, folders, video, version and date may differ; the frames listed grow with each run
// into the folder.
// The "render" part's checksum is the settings key in each frame's manifest
// (run/frame_manifest.h), so no frame rendered with other settings is ever skipped.
// The "render" part carries the file's format version (settings_format_version). A folder whose
// settings file has another version (or none: files before version 2) is refused like other
// settings, with a message that says so, since its frames' keys no longer match either.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "steadylight/run/render_settings.h"

namespace steadylight {

/// What a run adds to its RenderSettings.
struct RunInfo {
    std::string scene_name;
    int width = 0, height = 0;  // the image size used
    std::vector<int> frames;    // selected by this run
    int threads = 0;
};

/// The shape of the settings file. 2: the photon settings once, under "photon", for the photon,
/// localized and frozen methods alike (version 1 had no number and also gave frozen renders a
/// "localized" part).
constexpr int settings_format_version = 2;

/// The settings file's content for a run (the settings of the chosen method only).
nlohmann::json make_settings_json(const RenderSettings& settings, const RunInfo& run);

/// A checksum of the "render" part of `settings_json`: 16 hex digits.
std::string settings_key(const nlohmann::json& settings_json);

/// `<out>/.steadylight.lock`: the output folder's lock file (base/lock_file.h), held while the
/// settings file is checked and written, so that many processes can share the folder.
std::string folder_lock_name(const std::string& out_dir);

/// `<out>/<scene>.settings.json`.
std::string settings_file_name(const std::string& out_dir, const std::string& scene_name);

/// Checks `settings_json` against the file at `path` from an earlier run, if there is one, and
/// writes it there (atomically) with the frames of both, all under the folder's lock. Throws InputError when the
/// "render" parts differ, unless `overwrite`.
void write_settings_file(const std::string& path, nlohmann::json settings_json, bool overwrite);

}  // namespace steadylight
