// World images: the equirectangular picture of the surroundings that a scene's world may name
// (scene/environment_map.h maps it onto directions as Blender's Environment Texture does), read
// from an EXR (RGB or RGBA; any compression OpenEXR reads) or a Radiance HDR file and checked
// before any light is computed from it.
//
// A pixel that is NaN or infinite, or clearly negative, is an error naming the first one, not a
// value clamped in silence: it has no meaning as radiance, the sampling distribution built from
// the image would be meaningless with it, and a clamp would hide a broken file behind a
// plausible render. Slightly negative values (down to 10% of the image's mean value) are read
// as 0, with a warning: lossy compression leaves them in good images (every world image Blender
// ships, DWAB-compressed EXRs, has hundreds, down to 2.5% of its mean).
#pragma once

#include <string>
#include <string_view>

#include "steadylight/base/image.h"
#include "steadylight/base/input_file.h"

namespace steadylight {

/// The image of the world image file `path` (which must lie where `inputs` allows), rows from
/// the top. Throws InputError naming the file: it cannot be read (missing, not a regular file),
/// is neither an EXR nor a Radiance HDR image or is damaged, is larger than the texture limits
/// (scene/image_decoding.h), is not twice as wide as it is high, or has NaN, infinite or clearly
/// negative pixels (the file's comment says which).
Image load_world_image(const std::string& path, const InputFolder& inputs = {});

/// The same checks on a file's content, named `where` in messages (for tests and fuzzing).
Image decode_world_image(std::string_view bytes, const std::string& where);

}  // namespace steadylight
