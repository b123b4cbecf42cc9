// Writing finished frames: linear half-float EXR (OpenEXR) and 8-bit sRGB PNG (stb). Each file
// is written under a temporary name in the same folder and renamed into place, so an interrupted
// run never leaves a truncated image behind.
#pragma once

#include <string>

#include "steadylight/base/image.h"

namespace steadylight {

/// Linear RGB radiance as a half-float EXR with channels R, G, B.
void write_exr(const std::string& path, const Image& image);
/// The image clamped to [0, 1] and encoded with the sRGB transfer curve.
void write_png(const std::string& path, const Image& image);
/// Reads the R, G, B channels of an EXR (for tests and tools).
Image read_exr(const std::string& path);

/// The sRGB transfer curve (IEC 61966-2-1) for a linear value in [0, 1].
float linear_to_srgb(float v);

}  // namespace steadylight
