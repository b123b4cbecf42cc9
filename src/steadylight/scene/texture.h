// Image textures (glTF 2.0 §3.8): decoded 8-bit RGBA images, and the references to them that
// materials hold (which image, which texture coordinates, the sampler's wrap modes and filter,
// and KHR_texture_transform). Sampling is bilinear on the full-resolution image, with sRGB
// decoded per texel before filtering; there are no mip-maps: a pixel's jittered camera samples
// filter the texture instead (docs/materials.md, "Textures"). This sits in scene/ because the ray
// tracer's alpha test reads it too.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "steadylight/base/color.h"
#include "steadylight/base/vec.h"

namespace steadylight {

/// An image as stored: rows top to bottom (glTF's uv (0, 0) is the top-left corner), four
/// 8-bit channels per texel, not yet decoded from sRGB.
struct TextureImage {
    std::string name;
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba;
};

enum class TextureWrap { repeat, clamp_to_edge, mirrored_repeat };
enum class TextureFilter { linear, nearest };

/// RGBA as four floats.
using Rgba = std::array<float, 4>;

/// A material's use of an image.
struct TextureRef {
    int image = -1;    // index into SceneDesc::images; -1: no texture
    int texcoord = 0;  // which TEXCOORD_n set (0 or 1)
    TextureWrap wrap_s = TextureWrap::repeat;
    TextureWrap wrap_t = TextureWrap::repeat;
    TextureFilter filter = TextureFilter::linear;
    // KHR_texture_transform: uv' = translate(offset) * rotate(rotation) * scale(scale) * uv.
    Vec2 offset;
    float rotation = 0;  // radians, counter-clockwise in uv space as the extension defines it
    Vec2 scale{1, 1};

    bool is_set() const { return image >= 0; }
    /// The texture coordinates after KHR_texture_transform.
    Vec2 transform(Vec2 uv) const;
};

/// The sRGB transfer function's inverse (IEC 61966-2-1) for an 8-bit value.
float srgb_to_linear(uint8_t v);

/// \brief The texture at `uv` (before the transform), bilinearly filtered (or nearest, as its
/// sampler says), wrapped as its sampler says. With `srgb` the RGB channels are decoded from sRGB
/// before filtering (base colour and emissive); alpha and data textures stay linear.
Rgba sample_texture(const TextureImage& image, const TextureRef& ref, Vec2 uv, bool srgb);

/// The image's average colour, decoded from sRGB when `srgb` (for a textured light's power).
Rgb average_color(const TextureImage& image, bool srgb);

}  // namespace steadylight
