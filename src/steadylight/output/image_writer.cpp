#include "steadylight/output/image_writer.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "steadylight/base/atomic_file.h"
#include "steadylight/base/check.h"
#include "steadylight/base/error.h"
#include "steadylight/base/input_file.h"
#include "steadylight/output/deflate.h"
#include "steadylight/scene/exr_reading.h"

namespace steadylight {
namespace {

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
    SL_CHECK(!layers.empty());
    const ExrLayer& first = layers.front();
    const int width = first.image ? first.image->width : first.grey->width;
    const int height = first.image ? first.image->height : first.grey->height;
    static_assert(sizeof(Rgb) == 3 * sizeof(float));  // r, g, b side by side
    std::vector<ExrChannelValues> channels;
    const auto add_channel = [&](const std::string& name, const Image& image, int component) {
        SL_CHECK(image.width == width && image.height == height);
        channels.push_back({name, reinterpret_cast<const float*>(image.pixels.data()) + component});
    };
    for (const ExrLayer& layer : layers) {
        SL_CHECK((layer.image == nullptr) != (layer.grey == nullptr));
        for (const auto& [name, component] :
             exr_layer_channels(layer.name, layer.grey != nullptr, layer.scalar_channel))
            if (layer.grey) {
                SL_CHECK(layer.grey->width == width && layer.grey->height == height);
                channels.push_back({name, layer.grey->pixels.data(), 1});
            } else {
                add_channel(name, *layer.image, component);
            }
        if (layer.alpha) add_channel(layer.name.empty() ? "A" : layer.name + ".A", *layer.alpha, 0);
    }
    write_binary_file(path, encode_exr(width, height, std::move(channels), type));
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
    std::vector<unsigned char> compressed;
    if (!append_deflated(filtered.data(), filtered.size(), deflate_zlib_bound(filtered.size()), compressed))
        throw std::runtime_error("PNG encoder failed");

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
