#include "steadylight/output/image_writer.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "steadylight/base/error.h"
#include "steadylight/output/atomic_file.h"

namespace steadylight {
namespace {

std::string channel_name(const std::string& layer, int c) {
    const std::string rgb[3] = {"R", "G", "B"};
    return layer.empty() ? rgb[c] : layer + "." + rgb[c];
}

}  // namespace

float linear_to_srgb(float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1 / 2.4f) - 0.055f;
}

void write_exr(const std::string& path, const std::vector<ExrLayer>& layers) {
    write_file_atomically(path, [&](const std::string& file) {
        const Image& first = *layers.front().image;
        Imf::Header header(first.width, first.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        Imf::FrameBuffer buffer;
        std::vector<std::vector<half>> channels;
        channels.reserve(layers.size() * 3);
        for (const ExrLayer& layer : layers) {
            for (int c = 0; c < 3; ++c) {
                std::vector<half>& channel = channels.emplace_back(layer.image->pixels.size());
                for (size_t i = 0; i < channel.size(); ++i) channel[i] = half(layer.image->pixels[i][c]);
                const std::string name = channel_name(layer.name, c);
                header.channels().insert(name, Imf::Channel(Imf::HALF));
                buffer.insert(name, Imf::Slice(Imf::HALF, reinterpret_cast<char*>(channel.data()), sizeof(half),
                                               sizeof(half) * size_t(first.width)));
            }
        }
        Imf::OutputFile out(file.c_str(), header);
        out.setFrameBuffer(buffer);
        out.writePixels(first.height);
    });
}

void write_exr(const std::string& path, const Image& image) { write_exr(path, {{"", &image}}); }

std::vector<unsigned char> encode_png(const Image& image) {
    std::vector<unsigned char> pixels(image.pixels.size() * 3);
    for (size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            pixels[3 * i + size_t(c)] = static_cast<unsigned char>(std::lround(255 * linear_to_srgb(image.pixels[i][c])));
    std::vector<unsigned char> png;
    const auto append = [](void* context, void* data, int size) {
        auto& out = *static_cast<std::vector<unsigned char>*>(context);
        const auto* bytes = static_cast<const unsigned char*>(data);
        out.insert(out.end(), bytes, bytes + size);
    };
    if (!stbi_write_png_to_func(append, &png, image.width, image.height, 3, pixels.data(), image.width * 3))
        throw std::runtime_error("PNG encoder failed");
    return png;
}

void write_png(const std::string& path, const Image& image) { write_binary_file(path, encode_png(image)); }

Image read_exr(const std::string& path, const std::string& layer) {
    try {
        Imf::InputFile in(path.c_str());
        const Imath::Box2i window = in.header().dataWindow();
        const int width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
        std::vector<float> channels[3];
        Imf::FrameBuffer buffer;
        for (int c = 0; c < 3; ++c) {
            if (!in.header().channels().findChannel(channel_name(layer, c)))
                throw std::runtime_error("no channel " + channel_name(layer, c));
            channels[c].resize(size_t(width) * size_t(height));
            char* origin = reinterpret_cast<char*>(channels[c].data()) -
                           (size_t(window.min.x) + size_t(window.min.y) * size_t(width)) * sizeof(float);
            buffer.insert(channel_name(layer, c), Imf::Slice(Imf::FLOAT, origin, sizeof(float), sizeof(float) * size_t(width)));
        }
        in.setFrameBuffer(buffer);
        in.readPixels(window.min.y, window.max.y);
        Image image(width, height);
        for (size_t i = 0; i < image.pixels.size(); ++i)
            image.pixels[i] = {channels[0][i], channels[1][i], channels[2][i]};
        return image;
    } catch (const std::exception& e) {
        throw InputError(path, std::string("cannot read EXR: ") + e.what());
    }
}

std::vector<ExrLayerInfo> read_exr_layers(const std::string& path) {
    try {
        Imf::InputFile in(path.c_str());
        std::vector<ExrLayerInfo> layers;
        const Imf::ChannelList& channels = in.header().channels();
        for (auto channel = channels.begin(); channel != channels.end(); ++channel) {
            const std::string full = channel.name();
            const size_t dot = full.rfind('.');
            const std::string layer = dot == std::string::npos ? "" : full.substr(0, dot);
            auto found = std::find_if(layers.begin(), layers.end(), [&](const ExrLayerInfo& l) { return l.name == layer; });
            if (found == layers.end()) found = layers.insert(layers.end(), {layer, {}});
            found->channels.push_back(dot == std::string::npos ? full : full.substr(dot + 1));
        }
        return layers;
    } catch (const std::exception& e) {
        throw InputError(path, std::string("cannot read EXR: ") + e.what());
    }
}

}  // namespace steadylight
