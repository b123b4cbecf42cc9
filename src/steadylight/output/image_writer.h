// Writing finished frames: linear half-float EXR (OpenEXR) and 8-bit sRGB PNG (stb). Each file
// is written under a temporary name in the same folder and renamed into place, so an interrupted
// run never leaves a truncated image behind.
#pragma once

#include <string>
#include <vector>

#include "steadylight/base/image.h"

namespace steadylight {

/// One named image in a multi-layer EXR: channels `<name>.R`, `<name>.G`, `<name>.B`, or plain
/// R, G, B for the empty name (the beauty image, which every viewer shows first).
struct ExrLayer {
    std::string name;
    const Image* image;
};

/// Linear RGB as a half-float EXR with the given layers (all of the same size).
void write_exr(const std::string& path, const std::vector<ExrLayer>& layers);
/// Linear RGB radiance as a half-float EXR with channels R, G, B.
void write_exr(const std::string& path, const Image& image);
/// The image clamped to [0, 1] and encoded with the sRGB transfer curve.
void write_png(const std::string& path, const Image& image);
/// The bytes of the PNG file write_png writes (for pages that embed images).
std::vector<unsigned char> encode_png(const Image& image);
/// Reads the R, G, B channels of one layer of an EXR (for tests and tools).
Image read_exr(const std::string& path, const std::string& layer = "");

/// One layer of an EXR as its header lists it: channels `<name>.<channel>`, or the channels
/// without a dot for the empty name.
struct ExrLayerInfo {
    std::string name;
    std::vector<std::string> channels;  // the part after the last '.', in header order
};

/// The layers of an EXR file, from its header only, in the order of their first channel.
/// Throws InputError naming the file when it cannot be read.
std::vector<ExrLayerInfo> read_exr_layers(const std::string& path);

/// The sRGB transfer curve (IEC 61966-2-1) for a linear value in [0, 1].
float linear_to_srgb(float v);

}  // namespace steadylight
