// How a resumed render knows that a frame is finished. After writing a frame's files (each one
// atomically, base/atomic_file.h), the renderer writes `<scene>_<frame:04>.manifest.json`,
// last and atomically too: the name, size in bytes and 64-bit checksum (base/hash.h) of each
// file, and the key of the settings the frame was rendered with (run/settings_file.h). A
// frame is complete when its manifest reads, has the current settings key, and every file it
// lists exists with that size and checksum. So a frame cut short (no manifest), a file truncated
// or replaced later, or a frame from other settings is rendered again; nothing depends on which
// files a method writes. Frames written before manifests existed count as not rendered.
#pragma once

#include <string>
#include <vector>

namespace steadylight {

/// `<out>/<scene>_<frame:04>.manifest.json`.
std::string frame_manifest_name(const std::string& out_dir, const std::string& scene_name, int frame);

/// Writes the manifest of a frame whose files are `files` (paths inside `out_dir`).
void write_frame_manifest(const std::string& out_dir, const std::string& scene_name, int frame,
                          const std::vector<std::string>& files, const std::string& settings_key);

/// Whether a frame's outputs are complete; if not, why (empty when there is no manifest at all,
/// the usual case of a frame never rendered).
struct FrameCheck {
    bool complete = false;
    std::string problem;
};

FrameCheck check_frame_outputs(const std::string& out_dir, const std::string& scene_name, int frame,
                               const std::string& settings_key);

}  // namespace steadylight
