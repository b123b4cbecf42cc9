// The settings a render actually used, written beside its frames as `<out>/<scene>.settings.json`
// (STYLE.md §5): the scene file, method, image size, every setting of the method, the frames,
// threads, video, steadylight version and date. Its "render" part holds what the images depend
// on — the scene (name and checksum of the scene file), method, size, --aov, the output settings
// (EXR pixel type, exposure, view transform, dither; not --video) and the method's settings —
// and a resumed run must match it: otherwise render_animation() stops with an InputError naming
// the differences (frames from two settings would mix silently), unless --overwrite, which
// renders the selected frames again and replaces the file. Frames, threads, folders, video,
// version and date may differ; the frames listed grow with each run into the folder.
// The "render" part's checksum is the settings key in each frame's manifest
// (output/frame_manifest.h), so no frame rendered with other settings is ever skipped.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "steadylight/render.h"

namespace steadylight {

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(PhotonSettings, global_photons, caustic_photons, max_bounces)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(DensitySettings, k, max_radius)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(GatherSettings, theta_strata, phi_strata, fixed_directions)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(CacheSettings, accuracy, min_spacing_px, max_spacing_px)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(ShadingSettings, samples_per_pixel, direct_samples, max_specular_depth,
                                                caustic_estimate)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(PhotonMappingSettings, photons, irradiance_estimate, irradiance_stride,
                                                gather, cache, shading)
// `base` and `frozen` come from the photon settings and the method.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(LocalizedSettings, influence_photons, correction_estimate,
                                                influence_step, tau_lower, tau_upper)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(PathTracerSettings, samples_per_pixel, max_depth,
                                                roulette_start_depth, seed)

/// What a run adds to its RenderSettings.
struct RunInfo {
    std::string scene_name;
    int width = 0, height = 0;  // the image size used
    std::vector<int> frames;    // selected by this run
    int threads = 0;
};

/// The settings file's content for a run (the settings of the chosen method only).
nlohmann::json make_settings_json(const RenderSettings& settings, const RunInfo& run);

/// A checksum of the "render" part of `settings_json`: 16 hex digits.
std::string settings_key(const nlohmann::json& settings_json);

/// `<out>/<scene>.settings.json`.
std::string settings_file_name(const std::string& out_dir, const std::string& scene_name);

/// Checks `settings_json` against the file at `path` from an earlier run, if there is one, and
/// writes it there (atomically) with the frames of both. Throws InputError when the "render"
/// parts differ, unless `overwrite`.
void write_settings_file(const std::string& path, nlohmann::json settings_json, bool overwrite);

}  // namespace steadylight
