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

void write_png(const std::string& path, const Image& image) {
    write_file_atomically(path, [&](const std::string& file) {
        std::vector<unsigned char> bytes(image.pixels.size() * 3);
        for (size_t i = 0; i < image.pixels.size(); ++i)
            for (int c = 0; c < 3; ++c)
                bytes[3 * i + size_t(c)] = static_cast<unsigned char>(std::lround(255 * linear_to_srgb(image.pixels[i][c])));
        if (!stbi_write_png(file.c_str(), image.width, image.height, 3, bytes.data(), image.width * 3))
            throw std::runtime_error("PNG encoder failed");
    });
}

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

}  // namespace steadylight
