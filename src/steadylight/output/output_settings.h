// What the written files look like, besides the rendering itself: the EXR pixel type, the view
// transform of the PNGs, and the optional video of the PNG sequence (docs/usage.md, "Outputs").
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "steadylight/base/settings_check.h"
#include "steadylight/output/image_writer.h"
#include "steadylight/output/view_transform.h"

namespace steadylight {

struct OutputSettings {
    ExrPixelType exr_type = ExrPixelType::half;
    ViewTransform view;      // PNGs (and so the video)
    std::string video_file;  // empty: no video; else an H.264 MP4 of the PNG sequence
};

/// What shapes the written images: the settings file's "render" part holds it
/// (run/settings_file.h). The video is left out, since it does not change the frames.
inline void to_json(nlohmann::json& json, const OutputSettings& s) {
    json = {{"exr_type", s.exr_type == ExrPixelType::half ? "half" : "float"},
            {"exposure_ev", s.view.exposure_ev},
            {"view_transform", s.view.curve == ViewCurve::filmic ? "filmic" : "standard"},
            {"dither", s.view.dither}};
}

/// Throws InputError for an exposure out of range (or NaN).
inline void validate(const OutputSettings& s) {
    check_setting_range("/output/exposure_ev", s.view.exposure_ev, -64.0f, 64.0f);
}

}  // namespace steadylight
