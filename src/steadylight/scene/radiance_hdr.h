// Decoding Radiance HDR images (.hdr, .pic: RGBE pixels, Greg Ward's format, in which many
// environment images come). Our own decoder rather than stb_image's: the stb_image of Debian 12
// (2.27) loops forever on run-length data that ends inside a scanline (it reads a run of length
// zero again and again; a 48-byte file hangs it), which cannot be ruled out from outside.
//
// Read as Radiance itself reads them: a header of lines up to an empty line (FORMAT=32-bit_rle_rgbe
// or no FORMAT line; other lines such as EXPOSURE are ignored, as Blender ignores them), the
// standard orientation "-Y height +X width" (rows from the top, left to right), then each
// scanline run-length encoded (widths 8 to 32767, as Radiance writes them) or flat. A pixel
// (r, g, b, e) is ((r, g, b) + 0.5) 2^(e - 136), 0 when e = 0: the middle of the interval the
// byte stands for, as Radiance's colr_color and Blender compute it.
#pragma once

#include <string>
#include <string_view>

#include "steadylight/base/image.h"
#include "steadylight/scene/image_decoding.h"

namespace steadylight {

/// Whether `bytes` begin as a Radiance HDR file does ("#?", then the program's name).
bool is_radiance_hdr(std::string_view bytes);

/// The image of the Radiance HDR file whose content is `bytes`. Throws InputError naming
/// `where`: "not a Radiance HDR image (...)" or "a damaged Radiance HDR image (...)" saying what is
/// wrong, or what `check_size` throws (called once the header is read).
Image decode_radiance_hdr(std::string_view bytes, const std::string& where, const ImageSizeCheck& check_size = {});

}  // namespace steadylight
