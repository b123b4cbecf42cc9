// The layers of a frame's multi-layer EXR, as compositors (Nuke, Blender, Natron) read them: the
// final image as the default R, G, B (what plain viewers show, Nuke's `rgba`; with a
// transparent background R, G, B, A) and again as the named layer `beauty`, then every AOV as
// `<name>.R/G/B`, or as the single channel `<name>.Y` for the grey ones (influence and the
// record masks). Which AOVs a method has, and which are grey, is the method table's to say
// (methods/method.h).
#pragma once

#include <string>
#include <vector>

#include "steadylight/base/image.h"
#include "steadylight/output/image_writer.h"

namespace steadylight {

/// The EXR layers of a frame: "" and "beauty" for `beauty`, then `aovs` in order. With `alpha`
/// (a transparent background) both beauty layers have an A channel too; the AOVs have none, as
/// Blender's passes have none. The result points into `beauty`, `aovs` and `alpha`, which must
/// outlive it.
std::vector<ExrLayer> frame_exr_layers(const Image& beauty, const std::vector<NamedImage>& aovs,
                                       const Image* alpha = nullptr);

/// The same layers named as Blender's render result names its passes in view layer
/// `view_layer` (what RenderResult.load_from_file reads): the beauty once, as
/// `<view_layer>.Combined` with its A channel (`alpha`: ones for an opaque frame), then each AOV as
/// `<view_layer>.<name>`, a grey one with the single channel X.
std::vector<ExrLayer> blender_exr_layers(const std::string& view_layer, const Image& beauty,
                                         const std::vector<NamedImage>& aovs, const Image& alpha);

/// The values of a frame's layers that were not finite (NaN, an infinity). No layer may hold
/// one: it is a defect upstream, and a compositor's blur would spread it over the image.
struct NonFiniteValues {
    long count = 0;           // channel values
    std::string first_layer;  // where the first one was ("beauty" for the beauty)
    int first_x = 0, first_y = 0;
};

/// Replaces every non-finite channel value of `beauty` and `aovs` by 0 and says where they were.
NonFiniteValues replace_non_finite(Image& beauty, std::vector<NamedImage>& aovs);

}  // namespace steadylight
