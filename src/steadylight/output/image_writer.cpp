#include "steadylight/output/image_writer.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <zlib.h>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "steadylight/base/atomic_file.h"
#include "steadylight/base/error.h"
#include "steadylight/base/input_file.h"
#include "steadylight/scene/exr_reading.h"

namespace steadylight {
namespace {

/// The largest finite half: above it a half is +inf, which a compositor's blur would spread over
/// the image.
constexpr float max_half = 65504.0f;

/// `value` as a half, clamped to +-max_half. A NaN (which render_frame has replaced already,
/// output/frame_layers.h) becomes 0 here too.
half to_finite_half(float value) {
    return std::isnan(value) ? half(0.0f) : half(std::clamp(value, -max_half, max_half));
}

/// `count` values, every third float from `floats` (one channel of an image's Rgb), as
/// to_finite_half makes them.
void to_finite_halves_one_by_one(const float* floats, half* out, size_t count) {
    for (size_t i = 0; i < count; ++i) out[i] = to_finite_half(floats[3 * i]);
}

#if defined(__x86_64__)
/// The same with the F16C instructions, eight values at a time, in a sixth of the time: the same
/// halves, since both round to the nearest (ties to even), denormals too. A NaN fails the
/// ordered comparison and is masked to +0, as to_finite_half has it.
__attribute__((target("avx,f16c"))) void to_finite_halves_f16c(const float* floats, half* out, size_t count) {
    const __m256 lowest = _mm256_set1_ps(-max_half), highest = _mm256_set1_ps(max_half);
    size_t i = 0;
    for (; i + 8 <= count; i += 8) {
        const float* f = floats + 3 * i;
        const __m256 v = _mm256_setr_ps(f[0], f[3], f[6], f[9], f[12], f[15], f[18], f[21]);
        const __m256 is_number = _mm256_cmp_ps(v, v, _CMP_ORD_Q);
        const __m256 finite = _mm256_and_ps(_mm256_min_ps(_mm256_max_ps(v, lowest), highest), is_number);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i),
                         _mm256_cvtps_ph(finite, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC));
    }
    to_finite_halves_one_by_one(floats + 3 * i, out + i, count - i);
}
#endif

/// to_finite_halves_one_by_one, with F16C where the processor has it.
void to_finite_halves(const float* floats, half* out, size_t count) {
    static_assert(sizeof(half) == 2);
#if defined(__x86_64__)
    static const bool has_f16c = __builtin_cpu_supports("avx") && __builtin_cpu_supports("f16c");
    if (has_f16c) return to_finite_halves_f16c(floats, out, count);
#endif
    to_finite_halves_one_by_one(floats, out, count);
}

/// Lines a half EXR is converted and written in at a time (a multiple of ZIP's 16-line blocks).
constexpr int half_lines = 64;

/// One channel of the file: where its floats are in an image, and for a half file the halves of
/// the lines being written.
struct Channel {
    std::string name;
    const float* floats;  // its value at pixel i is floats[3 i]
    std::vector<half> halves;
};

Imf::PixelType imf_type(ExrPixelType type) { return type == ExrPixelType::half ? Imf::HALF : Imf::FLOAT; }

/// zlib's level for an EXR's ZIP blocks: a 1280x960 frame's 32 half channels compress in half
/// the time of OpenEXR's default level (4) into files 8% larger. A frame is written beside the
/// next one's rendering, and on few cores its compression takes from it.
constexpr int exr_zip_level = 1;

/// zlib's level for a PNG's pixels: with every row Paeth-filtered, a 1280x960 frame encodes in
/// 85 ms into 0.92 MB, where stb_image_write took 300 ms for 1.2 MB.
constexpr int png_zlib_level = 1;

/// PNG's predictor of a byte from the bytes left of it, above it and above-left of it.
int paeth_predictor(int left, int up, int up_left) {
    const int estimate = left + up - up_left;
    const int to_left = std::abs(estimate - left), to_up = std::abs(estimate - up),
              to_up_left = std::abs(estimate - up_left);
    if (to_left <= to_up && to_left <= to_up_left) return left;
    return to_up <= to_up_left ? up : up_left;
}

void append_big_endian(std::vector<unsigned char>& out, uint32_t value) {
    for (const int shift : {24, 16, 8, 0}) out.push_back(static_cast<unsigned char>(value >> shift));
}

/// A PNG chunk: the data's length, the type, the data, and the CRC of type and data.
void append_png_chunk(std::vector<unsigned char>& png, const char (&type)[5], const std::vector<unsigned char>& data) {
    append_big_endian(png, uint32_t(data.size()));
    const size_t type_at = png.size();
    png.insert(png.end(), type, type + 4);
    png.insert(png.end(), data.begin(), data.end());
    const uLong crc = crc32(0, png.data() + type_at, uInt(png.size() - type_at));
    append_big_endian(png, uint32_t(crc));
}

}  // namespace

ExrPixelType parse_exr_pixel_type(const std::string& name, const std::string& option) {
    if (name == "half") return ExrPixelType::half;
    if (name == "float") return ExrPixelType::float32;
    throw InputError(option, "unknown EXR pixel type \"" + name + "\" (half or float)");
}

void write_exr(const std::string& path, const std::vector<ExrLayer>& layers, ExrPixelType type) {
    write_file_atomically(path, [&](const std::string& file) {
        const Image& first = *layers.front().image;
        const int width = first.width, height = first.height;
        Imf::Header header(width, height);
        header.compression() = Imf::ZIP_COMPRESSION;
        header.zipCompressionLevel() = exr_zip_level;
        static_assert(sizeof(Rgb) == 3 * sizeof(float));  // r, g, b side by side
        std::vector<Channel> channels;
        const auto add_channel = [&](const std::string& name, const Image& image, int component) {
            header.channels().insert(name, Imf::Channel(imf_type(type)));
            channels.push_back({name, reinterpret_cast<const float*>(image.pixels.data()) + component, {}});
        };
        for (const ExrLayer& layer : layers) {
            for (const auto& [name, component] : exr_layer_channels(layer.name, layer.scalar, layer.scalar_channel))
                add_channel(name, *layer.image, component);
            if (layer.alpha) add_channel(layer.name.empty() ? "A" : layer.name + ".A", *layer.alpha, 0);
        }
        // OpenEXR compresses blocks of scanlines on its own threads, one per core; the bytes
        // written do not depend on how many.
        Imf::OutputFile out(file.c_str(), header, int(std::max(1u, std::thread::hardware_concurrency())));
        const size_t line = size_t(width);
        if (type == ExrPixelType::float32) {
            // Straight from the images' floats.
            Imf::FrameBuffer buffer;
            for (const Channel& channel : channels)
                buffer.insert(channel.name,
                              Imf::Slice(Imf::FLOAT, const_cast<char*>(reinterpret_cast<const char*>(channel.floats)),
                                         sizeof(Rgb), sizeof(Rgb) * line));
            out.setFrameBuffer(buffer);
            out.writePixels(height);
            return;
        }
        // Halves are converted a few lines at a time, so that a frame's dozen layers are never
        // copied whole while it is written. A slice addresses lines by their number in the
        // image: each batch's buffer is placed where its first line would be.
        for (Channel& channel : channels) channel.halves.resize(half_lines * line);
        for (int y0 = 0; y0 < height; y0 += half_lines) {
            const int lines = std::min(half_lines, height - y0);
            Imf::FrameBuffer buffer;
            for (Channel& channel : channels) {
                to_finite_halves(channel.floats + 3 * size_t(y0) * line, channel.halves.data(), size_t(lines) * line);
                char* base =
                    reinterpret_cast<char*>(channel.halves.data()) - ptrdiff_t(y0) * ptrdiff_t(sizeof(half) * line);
                buffer.insert(channel.name, Imf::Slice(Imf::HALF, base, sizeof(half), sizeof(half) * line));
            }
            out.setFrameBuffer(buffer);
            out.writePixels(lines);
        }
    });
}

void write_exr(const std::string& path, const Image& image) { write_exr(path, {{"", &image}}); }

std::vector<unsigned char> encode_png(const Image& image, const ViewTransform& view, const Image* alpha) {
    const std::vector<unsigned char> pixels = encode_srgb8(image, view, alpha);
    const int components = alpha ? 4 : 3;
    const size_t row = size_t(image.width) * size_t(components);
    // Every row Paeth-filtered (the filter byte 4, then each byte less the Paeth predictor of
    // the bytes left, above and above-left of it, 0 outside the image).
    std::vector<unsigned char> filtered((row + 1) * size_t(image.height));
    for (size_t y = 0; y < size_t(image.height); ++y) {
        const unsigned char* in = pixels.data() + y * row;
        const unsigned char* above = y > 0 ? in - row : nullptr;
        unsigned char* out = filtered.data() + y * (row + 1);
        *out++ = 4;
        for (size_t i = 0; i < row; ++i) {
            const int left = i >= size_t(components) ? in[i - size_t(components)] : 0;
            const int up = above ? above[i] : 0;
            const int up_left = above && i >= size_t(components) ? above[i - size_t(components)] : 0;
            out[i] = static_cast<unsigned char>(in[i] - paeth_predictor(left, up, up_left));
        }
    }
    uLongf compressed_size = compressBound(uLong(filtered.size()));
    std::vector<unsigned char> compressed(compressed_size);
    if (compress2(compressed.data(), &compressed_size, filtered.data(), uLong(filtered.size()), png_zlib_level) != Z_OK)
        throw std::runtime_error("PNG encoder failed");
    compressed.resize(compressed_size);

    std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::vector<unsigned char> header;
    append_big_endian(header, uint32_t(image.width));
    append_big_endian(header, uint32_t(image.height));
    // 8 bits a channel, RGB (2) or RGBA (6), deflate, adaptive filters, no interlace.
    header.insert(header.end(), {8, static_cast<unsigned char>(alpha ? 6 : 2), 0, 0, 0});
    append_png_chunk(png, "IHDR", header);
    append_png_chunk(png, "IDAT", compressed);
    append_png_chunk(png, "IEND", {});
    return png;
}

void write_png(const std::string& path, const Image& image, const ViewTransform& view, const Image* alpha) {
    write_binary_file(path, encode_png(image, view, alpha));
}

Image read_exr(const std::string& path, const std::string& layer) {
    return decode_exr(read_input_file(path), path, layer);
}

std::vector<ExrChannelInfo> read_exr_channels(const std::string& path) {
    try {
        Imf::InputFile in(path.c_str());
        std::vector<ExrChannelInfo> channels;
        for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it)
            channels.push_back(
                {it.name(), it.channel().type == Imf::HALF ? ExrPixelType::half : ExrPixelType::float32});
        return channels;
    } catch (const std::exception& e) {
        throw InputError(path, std::string("cannot read EXR: ") + e.what());
    }
}

std::vector<float> read_exr_channel(const std::string& path, const std::string& channel) {
    try {
        Imf::InputFile in(path.c_str());
        if (!in.header().channels().findChannel(channel)) throw std::runtime_error("no channel " + channel);
        const Imath::Box2i window = in.header().dataWindow();
        const int width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
        std::vector<float> values(size_t(width) * size_t(height));
        Imf::FrameBuffer buffer;
        buffer.insert(
            channel, Imf::Slice::Make(Imf::FLOAT, values.data(), window, sizeof(float), sizeof(float) * size_t(width)));
        in.setFrameBuffer(buffer);
        in.readPixels(window.min.y, window.max.y);
        return values;
    } catch (const std::exception& e) {
        throw InputError(path, std::string("cannot read EXR: ") + e.what());
    }
}

std::vector<ExrLayerInfo> read_exr_layers(const std::string& path) {
    std::vector<ExrLayerInfo> layers;
    for (const ExrChannelInfo& channel : read_exr_channels(path)) {
        const size_t dot = channel.name.rfind('.');
        const std::string layer = dot == std::string::npos ? "" : channel.name.substr(0, dot);
        auto found = std::find_if(layers.begin(), layers.end(), [&](const ExrLayerInfo& l) { return l.name == layer; });
        if (found == layers.end()) found = layers.insert(layers.end(), {layer, {}});
        found->channels.push_back(dot == std::string::npos ? channel.name : channel.name.substr(dot + 1));
    }
    return layers;
}

}  // namespace steadylight
