// render_animation(): the program's table of contents. Load the scene, place it at each frame,
// render the frame with the chosen integrator and write it out (DESIGN.md §3).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "steadylight/integrators/path_tracer.h"
#include "steadylight/integrators/localized.h"
#include "steadylight/integrators/photon_mapping.h"
#include "steadylight/output/frame_selection.h"
#include "steadylight/output/output_settings.h"

namespace steadylight {

struct RenderSettings {
    std::string scene_file;
    std::string out_dir = "out";
    FrameSelection frames;              // default (no spans): every frame of the scene
    bool overwrite = false;             // render frames again whose outputs are complete already
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
    std::vector<int> frames_written;  // by this run
    int frames_skipped = 0;           // complete from an earlier run (output/frame_manifest.h)
    std::vector<int> frames_left;     // selected but not written: after an interrupt
    bool interrupted = false;         // stopped by Ctrl-C (base/checkpoint.h)
    double seconds = 0;
};

/// Renders the selected frames and writes `<out>/<scene>_<frame:04>.exr` (with AOV layers) and
/// `.png` for each, for photon mapping `<scene>_<frame:04>.stats.json`, then the frame's
/// manifest; and `<out>/<scene>.settings.json` before the first frame. Frames whose outputs are
/// complete are skipped unless `settings.overwrite`. An interrupt stops it at the next
/// checkpoint: the frame in progress is dropped and the summary says so.
RenderSummary render_animation(const RenderSettings& settings);

/// Runs the segment pass of the localized method for every segment and writes the static cache
/// files (`steadylight bake`), or leaves them when they match already. Returns their paths.
std::vector<std::string> bake_static_caches(const RenderSettings& settings);

/// A human-readable description of a scene: objects, triangles, lights, frames and the
/// static/dynamic split (`steadylight info`).
std::string describe_scene(const std::string& scene_file);

}  // namespace steadylight
