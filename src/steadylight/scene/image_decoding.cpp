// PNG through stb_image, built here for PNG alone (STBI_ONLY_PNG) and static (STB_IMAGE_STATIC)
// so that it does not meet Debian's libstb, whose stb_image_write the tests link. JPEG through
// libjpeg-turbo: the stb_image of Debian 12 predates fixes of JPEG defects our fuzzing found
// (Huffman tables of more than 256 codes written past their arrays, nothings/stb#1289; symbol
// indices out of range in stbi__jpeg_huff_decode, nothings/stb#1291), which cannot be ruled out
// from outside, while libjpeg-turbo is maintained and fuzzed upstream (OSS-Fuzz).
#include "steadylight/scene/image_decoding.h"

#include <cctype>
#include <climits>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <jpeglib.h>

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
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
namespace {

bool is_jpeg(const unsigned char* bytes, size_t size) {
    return size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
}

/// Sets `image.problem` when `width` x `height` exceeds the limits of image_decoding.h.
bool fits_the_limits(int64_t width, int64_t height, DecodedImage& image) {
    if (width <= max_image_side && height <= max_image_side && width * height <= max_image_texels) return true;
    image.problem = fmt::format("too large ({} x {} texels; at most {} on a side and 8192 x 8192 in all)", width,
                                height, max_image_side);
    image.too_large = true;
    return false;
}

/// What decode_png fixes or refuses before stb_image reads a PNG, from a walk over its chunks.
struct PngChunks {
    /// The PNG without its empty IDAT chunks, when it has any, else empty: from an empty first
    /// IDAT the stb_image of Debian 12 copies zero bytes to a null pointer (undefined behaviour,
    /// found by fuzzing). The chunks' CRCs stay valid; stb_image does not check them anyway.
    std::vector<unsigned char> without_empty_idat;
    /// The type of a chunk before IEND whose length runs past the end of the file, if any:
    /// stb_image allocates an IDAT's length (up to 4 GB) before it finds the data missing (a
    /// 152-byte file took a second; found by fuzzing).
    std::string truncated_chunk;
};

PngChunks walk_png_chunks(const unsigned char* bytes, size_t size) {
    constexpr size_t signature = 8, header = 8, chunk_overhead = 12;  // length and type; and the CRC
    PngChunks chunks;
    size_t at = signature, copied = 0;
    while (at + header <= size) {
        const size_t length =
            size_t(bytes[at]) << 24 | size_t(bytes[at + 1]) << 16 | size_t(bytes[at + 2]) << 8 | bytes[at + 3];
        const unsigned char* type = bytes + at + 4;
        if (std::memcmp(type, "IEND", 4) == 0) break;
        // A chunk cut short anywhere, its CRC too (a 43-byte file whose last chunk header said 2 GB).
        if (length + chunk_overhead > size - at) {
            for (int i = 0; i < 4; ++i) chunks.truncated_chunk += std::isalpha(type[i]) ? char(type[i]) : '?';
            break;
        }
        if (length == 0 && std::memcmp(type, "IDAT", 4) == 0) {
            chunks.without_empty_idat.insert(chunks.without_empty_idat.end(), bytes + copied, bytes + at);
            copied = at + chunk_overhead;
        }
        at += chunk_overhead + length;
    }
    if (copied > 0) chunks.without_empty_idat.insert(chunks.without_empty_idat.end(), bytes + copied, bytes + size);
    return chunks;
}

DecodedImage decode_png(const unsigned char* bytes, size_t size) {
    DecodedImage image;
    const PngChunks chunks = walk_png_chunks(bytes, size);
    if (!chunks.truncated_chunk.empty()) {
        image.problem =
            fmt::format("a damaged PNG image (its {} chunk runs past the end of the file)", chunks.truncated_chunk);
        return image;
    }
    if (!chunks.without_empty_idat.empty())
        return decode_png(chunks.without_empty_idat.data(), chunks.without_empty_idat.size());
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(bytes, int(size), &width, &height, &channels)) {
        image.problem = fmt::format("not a PNG or JPEG image ({})", stbi_failure_reason());
        return image;
    }
    if (!fits_the_limits(width, height, image)) return image;
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

/// libjpeg reports errors through error_exit, which must not return: it jumps back to
/// decode_jpeg with the message.
struct JpegErrors {
    jpeg_error_mgr manager;
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
};

[[noreturn]] void jump_back_with_the_message(j_common_ptr info) {
    JpegErrors* errors = reinterpret_cast<JpegErrors*>(info->err);
    (*info->err->format_message)(info, errors->message);
    std::longjmp(errors->jump, 1);
}

void ignore_warnings(j_common_ptr, int) {}

/// Decodes into `image` (the caller's, so that nothing this function changes after setjmp is an
/// automatic variable of it); false with image.problem set on failure.
bool read_jpeg(const unsigned char* bytes, size_t size, DecodedImage& image) {
    jpeg_decompress_struct info{};
    JpegErrors errors{};
    info.err = jpeg_std_error(&errors.manager);
    errors.manager.error_exit = jump_back_with_the_message;
    errors.manager.emit_message = ignore_warnings;
    if (setjmp(errors.jump)) {
        jpeg_destroy_decompress(&info);
        image.rgba.clear();
        image.problem = fmt::format("not a PNG or JPEG image (JPEG: {})", errors.message);
        return false;
    }
    jpeg_create_decompress(&info);
    jpeg_mem_src(&info, bytes, static_cast<unsigned long>(size));
    jpeg_read_header(&info, TRUE);
    if (!fits_the_limits(info.image_width, info.image_height, image)) {
        jpeg_destroy_decompress(&info);
        return false;
    }
    info.out_color_space = JCS_EXT_RGBA;  // grey and YCbCr alike, alpha 255
    jpeg_start_decompress(&info);
    image.width = int(info.output_width);
    image.height = int(info.output_height);
    image.rgba.resize(size_t(image.width) * size_t(image.height) * 4);
    while (info.output_scanline < info.output_height) {
        JSAMPROW row = image.rgba.data() + size_t(info.output_scanline) * size_t(image.width) * 4;
        jpeg_read_scanlines(&info, &row, 1);
    }
    jpeg_finish_decompress(&info);
    jpeg_destroy_decompress(&info);
    return true;
}

}  // namespace

DecodedImage decode_image(const unsigned char* bytes, size_t size) {
    if (!bytes || size == 0 || size > size_t(INT_MAX)) return {.problem = "not a PNG or JPEG image (no data)"};
    DecodedImage image;
    if (!is_jpeg(bytes, size)) return decode_png(bytes, size);
    if (!read_jpeg(bytes, size, image)) image.width = image.height = 0;
    return image;
}

}  // namespace steadylight
