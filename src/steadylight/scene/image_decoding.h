// Decoding the PNG and JPEG images of glTF textures (PNG with stb_image, built here for PNG only;
// JPEG with libjpeg-turbo: image_decoding.cpp says why), an image's size checked from its header
// before any pixel is decoded.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace steadylight {

/// The largest image decoded: 16384 texels on a side and 2^26 texels (8192 x 8192) in all, so
/// that one texture costs at most 256 MB as 8-bit RGBA (about three copies live while loading).
constexpr int max_image_side = 16384;
constexpr int64_t max_image_texels = int64_t(1) << 26;

/// Called with an image's size once its header is read and before its pixels are: it throws
/// to refuse the image (one too large, or of the wrong shape).
using ImageSizeCheck = std::function<void(int64_t width, int64_t height)>;

struct DecodedImage {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba;  // 8-bit RGBA, rows top to bottom; empty when not decoded
    /// Why the image was not decoded: "not a PNG or JPEG image (...)" or "too large (...)".
    std::string problem;
    bool too_large = false;
};

/// Decodes `size` bytes of a PNG or JPEG file into 8-bit RGBA.
DecodedImage decode_image(const unsigned char* bytes, size_t size);

}  // namespace steadylight
