// What the written files look like: the EXR pixel type and the AOV layers it holds, the view
// transform of the PNGs, whether the background is transparent (the world left out of what the
// camera sees directly, and an alpha channel in the EXR and the PNG), and the optional video of
// the PNG sequence (docs/usage.md, "Outputs").
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <utility>

#include <nlohmann/json.hpp>

#include "steadylight/base/error.h"
#include "steadylight/base/settings_check.h"
#include "steadylight/output/image_writer.h"
#include "steadylight/output/view_transform.h"

namespace steadylight {

/// Which AOV layers a frame's files get after the beauty (--layers; methods/method.h, LayerKind):
/// every one its method has, the light's terms only, or none. The method's analysis layers are
/// the paper's figures; at production sizes they are a third of an EXR's bytes.
enum class LayerSet { all, terms, beauty };

/// LayerSet's values as --layers and the settings file spell them.
constexpr std::array<std::pair<LayerSet, std::string_view>, 3> layer_set_names = {
    {{LayerSet::all, "all"}, {LayerSet::terms, "terms"}, {LayerSet::beauty, "beauty"}}};

inline std::string_view layer_set_name(LayerSet set) {
    for (const auto& [value, name] : layer_set_names)
        if (value == set) return name;
    return "all";
}

/// The LayerSet called `name`; an InputError naming `option` otherwise.
inline LayerSet parse_layer_set(const std::string& name, const std::string& option = "--layers") {
    for (const auto& [value, spelled] : layer_set_names)
        if (spelled == name) return value;
    throw InputError(option, "unknown layer set \"" + name + "\" (all, terms or beauty)");
}

struct OutputSettings {
    ExrPixelType exr_type = ExrPixelType::half;
    LayerSet layers = LayerSet::all;
    ViewTransform view;      // PNGs (and so the video)
    std::string video_file;  // empty: no video; else an H.264 MP4 of the PNG sequence
    /// Blender's Film > Transparent: the world seen directly by the camera is left out, and the
    /// frames get alpha, the share of each pixel's camera rays that met a surface (glass and
    /// mirrors count as surfaces: the world seen through them stays, as in Cycles by default).
    bool transparent_background = false;
    /// Non-empty: the EXR's channels are named as Blender's render result names them for this view
    /// layer (frame_layers.h), for the Blender add-on.
    std::string blender_view_layer;
};

/// What shapes the written images: the settings file's "render" part holds it
/// (run/settings_file.h). The video is left out, since it does not change the frames. A
/// transparent background is there only when chosen: the folders rendered before the option
/// existed hold opaque frames, and stay valid for a run that does not choose it; so are Blender's
/// channel names, and a layer set other than all (those folders hold every layer).
inline void to_json(nlohmann::json& json, const OutputSettings& s) {
    json = {{"exr_type", s.exr_type == ExrPixelType::half ? "half" : "float"},
            {"exposure_ev", s.view.exposure_ev},
            {"view_transform", s.view.curve == ViewCurve::filmic ? "filmic" : "standard"},
            {"dither", s.view.dither}};
    if (s.layers != LayerSet::all) json["layers"] = std::string(layer_set_name(s.layers));
    if (s.transparent_background) json["transparent_background"] = true;
    if (!s.blender_view_layer.empty()) json["blender_view_layer"] = s.blender_view_layer;
}

/// Throws InputError for an exposure out of range (or NaN).
inline void validate(const OutputSettings& s) {
    check_setting_range("/output/exposure_ev", s.view.exposure_ev, -64.0f, 64.0f);
}

}  // namespace steadylight
