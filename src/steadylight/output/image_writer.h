// Writing finished frames: linear multi-layer EXR (half or float, exr_encoder.h) and 8-bit sRGB
// PNG through the view transform of view_transform.h, both deflated by deflate.h. Each file is written under a
// temporary name in the same folder and renamed into place, so an interrupted run never leaves a truncated image
// behind.
#pragma once

#include <string>
#include <vector>

#include "steadylight/base/image.h"
#include "steadylight/output/exr_encoder.h"
#include "steadylight/output/view_transform.h"

namespace steadylight {

/// One named image in a multi-layer EXR: channels `<name>.R`, `<name>.G`, `<name>.B`, or plain
/// R, G, B for the empty name (what every viewer shows first, and Nuke's `rgba` layer). A grey
/// layer (`grey` rather than `image`) is stored as the single channel `<name>.Y` (OpenEXR's name
/// for a luminance-only channel). With `alpha` (a grey image, its red channel) the layer also has
/// `<name>.A`, or plain A: the colours are then premultiplied by it, as OpenEXR's convention has
/// them.
struct ExrLayer {
    std::string name;
    const Image* image;               // null for a grey layer
    const GreyImage* grey = nullptr;  // a grey layer's values
    const Image* alpha = nullptr;
    std::string scalar_channel = "Y";  // Blender names a grey pass's channel X
};

/// "half" or "float"; throws InputError naming `option` otherwise.
ExrPixelType parse_exr_pixel_type(const std::string& name, const std::string& option = "--exr-type");

/// Linear RGB as a ZIP-compressed EXR with the given layers (all of the same size).
void write_exr(const std::string& path, const std::vector<ExrLayer>& layers, ExrPixelType type = ExrPixelType::half);
/// Linear RGB radiance as a half-float EXR with channels R, G, B.
void write_exr(const std::string& path, const Image& image);
/// The image through `view` as the bytes of an 8-bit sRGB PNG file (for pages that embed images):
/// RGB, or with `alpha` RGBA, the image being premultiplied by it (encode_srgb8 says how).
std::vector<unsigned char> encode_png(const Image& image, const ViewTransform& view = {}, const Image* alpha = nullptr);
/// The image through `view` as an 8-bit sRGB PNG (encode_png written to `path`).
void write_png(const std::string& path, const Image& image, const ViewTransform& view = {},
               const Image* alpha = nullptr);
/// Reads one layer of an EXR (for tests and tools) with decode_exr (scene/exr_reading.h): its
/// R, G, B channels, or for a grey layer its Y channel copied into R, G and B. Throws InputError
/// naming the file.
Image read_exr(const std::string& path, const std::string& layer = "");

/// A channel of an EXR file as its header lists it (sorted by name).
struct ExrChannelInfo {
    std::string name;
    ExrPixelType type;
};
/// The channels of an EXR file, from its header only (for tests and tools).
/// Throws InputError naming the file when it cannot be read.
std::vector<ExrChannelInfo> read_exr_channels(const std::string& path);

/// One channel of an EXR file (`A`, `beauty.A`, ...) as floats, row by row from the top of the
/// data window (for tests and tools). Throws InputError naming the file when it cannot be read
/// or has no such channel.
std::vector<float> read_exr_channel(const std::string& path, const std::string& channel);

/// One layer of an EXR as its header lists it: channels `<name>.<channel>`, or the channels
/// without a dot for the empty name.
struct ExrLayerInfo {
    std::string name;
    std::vector<std::string> channels;  // the part after the last '.', in header order
};

/// The layers of an EXR file (read_exr_channels grouped by name), in the order of their first
/// channel. Throws InputError naming the file when it cannot be read.
std::vector<ExrLayerInfo> read_exr_layers(const std::string& path);

}  // namespace steadylight
