#include "steadylight/scene/world_image.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdint>

#include "steadylight/base/error.h"
#include "steadylight/scene/exr_reading.h"
#include "steadylight/scene/image_decoding.h"
#include "steadylight/scene/radiance_hdr.h"

namespace steadylight {
namespace {

/// The most negative a pixel value may be, as a share of the image's mean value, to count as
/// the noise of lossy compression (read as 0) rather than a broken image. Blender's own world
/// images (DWAB-compressed EXRs) go down to 2.5% of their mean.
constexpr float negative_noise_share = 0.1f;

/// Refuses, before its pixels are read, an image beyond the texture limits or not 2:1.
void check_world_image_size(int64_t width, int64_t height, const std::string& where) {
    if (width > max_image_side || height > max_image_side || width * height > max_image_texels)
        throw InputError(where, fmt::format("the world image is too large ({} x {} texels; at most {} on a side and "
                                            "8192 x 8192 in all)",
                                            width, height, max_image_side));
    if (width != 2 * height)
        throw InputError(where, fmt::format("the world image is {} x {} texels, but an equirectangular image is twice "
                                            "as wide as it is high",
                                            width, height));
}

/// Throws naming the first pixel (in rows from the top) for which `is_bad(pixel)`, how many are
/// and what they must be.
template <class IsBad>
void refuse_bad_pixels(const Image& image, const std::string& where, IsBad&& is_bad, const std::string& rule) {
    int64_t bad = 0, first = -1;
    for (size_t i = 0; i < image.pixels.size(); ++i)
        if (is_bad(image.pixels[i]) && bad++ == 0) first = int64_t(i);
    if (bad == 0) return;
    const Rgb& p = image.pixels[size_t(first)];
    throw InputError(
        where, fmt::format("pixel ({}, {}) of the world image is ({}, {}, {}): {}, and {} of its {} pixels "
                           "are not",
                           first % image.width, first / image.width, p.r, p.g, p.b, rule, bad, image.pixels.size()));
}

/// Refuses NaN, infinite and clearly negative pixels; sets slightly negative components to 0.
void check_world_image_pixels(Image& image, const std::string& where) {
    refuse_bad_pixels(
        image, where, [](Rgb p) { return !is_finite(p); }, "radiance must be finite");
    double sum = 0;
    for (const Rgb& p : image.pixels) sum += double(std::max(p.r, 0.0f)) + std::max(p.g, 0.0f) + std::max(p.b, 0.0f);
    const float mean = float(sum / (3.0 * double(image.pixels.size())));
    const float lowest = -negative_noise_share * mean;
    refuse_bad_pixels(
        image, where,
        [&](Rgb p) {
            return std::min({p.r, p.g, p.b}) < lowest;
        },
        fmt::format("radiance must not be negative (beyond {}, {}% of the image's mean value, as lossy compression's "
                    "noise may be)",
                    lowest, 100 * negative_noise_share));
    int64_t clamped = 0;
    float most_negative = 0;
    for (Rgb& p : image.pixels)
        for (float* c : {&p.r, &p.g, &p.b})
            if (*c < 0) {
                most_negative = std::min(most_negative, *c);
                *c = 0;
                ++clamped;
            }
    if (clamped > 0)
        spdlog::warn(
            "{}: {} pixel values of the world image are slightly negative (down to {}; its mean value is {}), "
            "as lossy compression leaves them: they read as 0",
            where, clamped, most_negative, mean);
}

}  // namespace

Image decode_world_image(std::string_view bytes, const std::string& where) {
    const ImageSizeCheck check_size = [&](int64_t width, int64_t height) {
        check_world_image_size(width, height, where);
    };
    Image image;
    if (is_exr(bytes))
        image = decode_exr(bytes, where, "", check_size);
    else if (is_radiance_hdr(bytes))
        image = decode_radiance_hdr(bytes, where, check_size);
    else
        throw InputError(where, "not an EXR or Radiance HDR image, which a world image must be");
    check_world_image_pixels(image, where);
    return image;
}

Image load_world_image(const std::string& path, const InputFolder& inputs) {
    return decode_world_image(read_input_file(path, inputs), path);
}

}  // namespace steadylight
