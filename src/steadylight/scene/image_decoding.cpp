// stb_image's implementation lives in this file alone, static (STB_IMAGE_STATIC) so that it does
// not meet Debian's libstb (linked for stb_image_write), with PNG and JPEG only and no stdio.
#include "steadylight/scene/image_decoding.h"

#include <climits>

#include <fmt/format.h>

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#endif
#include <stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace steadylight {

DecodedImage decode_image(const unsigned char* bytes, size_t size) {
    DecodedImage image;
    if (!bytes || size == 0 || size > size_t(INT_MAX)) {
        image.problem = "not a PNG or JPEG image (no data)";
        return image;
    }
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(bytes, int(size), &width, &height, &channels)) {
        image.problem = fmt::format("not a PNG or JPEG image ({})", stbi_failure_reason());
        return image;
    }
    if (width > max_image_side || height > max_image_side ||
        int64_t(width) * int64_t(height) > max_image_texels) {
        image.problem = fmt::format("too large ({} x {} texels; at most {} on a side and {} x {} in all)",
                                    width, height, max_image_side, 8192, 8192);
        image.too_large = true;
        return image;
    }
    stbi_uc* pixels = stbi_load_from_memory(bytes, int(size), &width, &height, &channels, 4);
    if (!pixels) {
        image.problem = fmt::format("not a PNG or JPEG image ({})", stbi_failure_reason());
        return image;
    }
    image.width = width;
    image.height = height;
    image.rgba.assign(pixels, pixels + size_t(width) * size_t(height) * 4);
    stbi_image_free(pixels);
    return image;
}

}  // namespace steadylight
