// render_animation(): the program's table of contents. Load the scene, place it at each frame,
// render the frame with the chosen integrator and write it out (DESIGN.md §3).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "steadylight/integrators/path_tracer.h"
#include "steadylight/integrators/localized.h"
#include "steadylight/integrators/photon_mapping.h"
#include "steadylight/output/output_settings.h"

namespace steadylight {

struct FrameRange {
    int first = 0;
    int last = 0;  // inclusive
};

/// Parses "N" or "A-B" (inclusive). Throws InputError for anything else or for B < A.
FrameRange parse_frame_range(const std::string& text);

struct RenderSettings {
    std::string scene_file;
    std::string out_dir = "out";
    std::optional<FrameRange> frames;  // default: every frame of the scene
    std::optional<int> width, height;  // default: the scene camera's resolution
    /// "localized" (the paper's method), "photon" (photon mapping every frame from scratch, the
    /// paper's reference), "frozen" (static cache reused as it is) or "path" (ground truth).
    std::string method = "localized";
    PathTracerSettings path;
    PhotonMappingSettings photon;       // also the base of the localized and frozen methods
    LocalizedSettings localized;        // its `base` and `frozen` are filled in from the above
    std::string cache_file;             // static cache file; default <out>/<scene>.irrcache
    bool show_progress = true;
    bool aov_pngs = false;              // also write each EXR layer as <scene>_<frame:04>.<layer>.png
    OutputSettings output;              // EXR pixel type, PNG view transform, --video
};

struct RenderSummary {
    int frames_written = 0;
    double seconds = 0;
};

/// Renders the frames and writes `<out>/<scene>_<frame:04>.exr` (with AOV layers) and `.png`
/// for each, and for photon mapping `<scene>_<frame:04>.stats.json`.
RenderSummary render_animation(const RenderSettings& settings);

/// Runs the segment pass of the localized method for every segment and writes the static cache
/// files (`steadylight bake`), or leaves them when they match already. Returns their paths.
std::vector<std::string> bake_static_caches(const RenderSettings& settings);

/// A human-readable description of a scene: objects, triangles, lights, frames and the
/// static/dynamic split (`steadylight info`).
std::string describe_scene(const std::string& scene_file);

}  // namespace steadylight
