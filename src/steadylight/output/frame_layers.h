// The layers of a frame's multi-layer EXR, as compositors (Nuke, Blender, Natron) read them: the
// final image as the default R, G, B (what plain viewers show, Nuke's `rgba`) and again as the
// named layer `beauty`, then every AOV as `<name>.R/G/B`, or as the single channel `<name>.Y`
// for the grey ones (influence and the record masks).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "steadylight/output/image_writer.h"

namespace steadylight {

/// True for the AOVs that hold one value per pixel (written as `<name>.Y`).
bool is_scalar_layer(const std::string& name);

/// The EXR layers of a frame: "" and "beauty" for `beauty`, then `aovs` in order. The result
/// points into `beauty` and `aovs`, which must outlive it.
std::vector<ExrLayer> frame_exr_layers(const Image& beauty, const std::vector<std::pair<std::string, Image>>& aovs);

}  // namespace steadylight
