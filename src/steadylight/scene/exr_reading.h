// Reading EXR images (OpenEXR) as linear RGB: one layer's R, G and B channels, or the Y channel of
// a grey layer. The headers are read first by OpenEXRCore, the library's newer C reader, which
// checks them against the file before taking memory (exr_reading.cpp says why), then the pixels
// by the C++ library. It sits in scene/ because world images are scene input (world_image.h);
// the writer's read_exr (output/image_writer.h: frames, for tests and tools) reads through it.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "steadylight/base/image.h"
#include "steadylight/scene/image_decoding.h"

namespace steadylight {

/// The EXR channel names of a layer and the colour component (0, 1, 2) each holds:
/// `<layer>.R`, `<layer>.G`, `<layer>.B`, or `<layer>.Y` alone for a scalar (grey) layer; plain
/// R, G, B or Y for the empty name.
std::vector<std::pair<std::string, int>> exr_layer_channels(const std::string& layer, bool scalar,
                                                            const std::string& scalar_channel = "Y");

/// Whether `bytes` begin with the EXR magic number.
bool is_exr(std::string_view bytes);

/// One layer of the EXR file whose content is `bytes`: its R, G, B channels (any alpha ignored),
/// or, when it has a Y channel, that one copied into R, G and B. Rows from the top of the data
/// window. Throws InputError naming `where`: "cannot read EXR: ..." when the file is damaged or
/// lacks the channels, or what `check_size` throws (called with the data window's size).
Image decode_exr(std::string_view bytes, const std::string& where, const std::string& layer = "",
                 const ImageSizeCheck& check_size = {});

}  // namespace steadylight
