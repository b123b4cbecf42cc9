// render_animation(): the program's table of contents. Load the scene, place it at each frame,
// render the frame with the chosen integrator and write it out (DESIGN.md §3).
#pragma once

#include <optional>
#include <string>

#include "steadylight/integrators/path_tracer.h"
#include "steadylight/integrators/photon_mapping.h"

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
    std::string method = "path";  // "path" (ground truth) or "photon" (photon mapping, paper's reference)
    PathTracerSettings path;
    PhotonMappingSettings photon;
    bool show_progress = true;
};

struct RenderSummary {
    int frames_written = 0;
    double seconds = 0;
};

/// Renders the frames and writes `<out>/<scene>_<frame:04>.exr` (with AOV layers) and `.png`
/// for each, and for photon mapping `<scene>_<frame:04>.stats.json`.
RenderSummary render_animation(const RenderSettings& settings);

/// A human-readable description of a scene: objects, triangles, lights, frames and the
/// static/dynamic split (`steadylight info`).
std::string describe_scene(const std::string& scene_file);

}  // namespace steadylight
