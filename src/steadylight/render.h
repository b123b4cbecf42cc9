// render_animation(): the program's table of contents. Load the scene; for each segment, its
// static pass (when the method has one); for each selected frame of it, the frame pass of the
// chosen method; then write the frame (docs/design.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "steadylight/run/render_settings.h"

namespace steadylight {

struct RenderSummary {
    std::vector<int> frames_written;              // by this run
    int frames_skipped = 0;                       // complete from an earlier run (run/frame_manifest.h)
    std::vector<int> frames_claimed_elsewhere;    // still claimed by another process when interrupted
    std::vector<int> frames_completed_elsewhere;  // finished by another process while this one ran
    std::vector<int> frames_left;                 // selected but not written: after an interrupt
    bool interrupted = false;                     // stopped by Ctrl-C (base/checkpoint.h)
    double seconds = 0;
};

/// Renders the selected frames and writes `<out>/<scene>_<frame:04>.exr` (with AOV layers) and
/// `.png` for each, its statistics `<scene>_<frame:04>.stats.json`, then the frame's
/// manifest; and `<out>/<scene>.settings.json` before the first frame. Frames whose outputs are
/// complete are skipped unless `settings.overwrite`; each frame is claimed first, and one that
/// another process holds is waited for at the end: completed by its holder, or taken over when
/// its holder dies (run/frame_claim.h). With `settings.check_complete`
/// nothing is rendered: an InputError lists the selected frames that are not complete. An
/// interrupt stops it at the next checkpoint: the frame in progress is dropped and the summary
/// says so.
RenderSummary render_animation(const RenderSettings& settings);

/// Runs the segment pass (of the localized and frozen methods) for every segment, or only for
/// `only_segment` (an index into Scene::segments(); InputError when out of range), and writes
/// the static cache files (`steadylight bake`), or leaves them when they match already. Returns
/// their paths.
std::vector<std::string> bake_static_caches(const RenderSettings& settings,
                                            std::optional<int> only_segment = std::nullopt);

/// A human-readable description of a scene: objects, triangles, lights, frames and the
/// static/dynamic split (`steadylight info`).
std::string describe_scene(const std::string& scene_file, bool confine_inputs = false);

}  // namespace steadylight
