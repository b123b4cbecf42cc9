// What a run is asked to do: the scene, the output folder, the frames, the method and its
// settings, the image size and the output options (`steadylight render` and `bake`). Each part's
// JSON and validation sit beside its own struct; validate() checks the whole before any work.
#pragma once

#include <optional>
#include <string>

#include "steadylight/methods/method.h"
#include "steadylight/output/output_settings.h"
#include "steadylight/run/frame_selection.h"

namespace steadylight {

struct RenderSettings : MethodSettings {
    std::string scene_file;
    std::string out_dir = "out";
    FrameSelection frames;             // default (no spans): every frame of the scene
    bool overwrite = false;            // render frames again whose outputs are complete already
    std::optional<int> width, height;  // default: the scene camera's resolution
    std::string cache_file;            // static cache file; default <out>/<scene>.irrcache
    bool require_cache = false;        // a missing or stale static cache is an error, not computed
    bool check_complete = false;       // render nothing: an error listing the selected frames not complete
    bool confine_inputs = false;       // the scene's files only from its own folder (not in the settings file)
    bool show_progress = true;
    bool aov_pngs = false;  // also write each EXR layer as <scene>_<frame:04>.<layer>.png
    bool reuse = true;      // photon paths kept per segment, retraced where dynamic objects
                            // meet them, and pixels reused for a still camera (localized;
                            // the images are the same either way: --no-reuse)
    OutputSettings output;  // EXR pixel type, PNG view transform, --video
};

/// Checks the image size and the chosen method's settings (render_animation and
/// bake_static_caches call it first); throws InputError naming the setting.
void validate(const RenderSettings& settings);

}  // namespace steadylight
