#include "steadylight/scene/exr_reading.h"

#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <exception>

#include "steadylight/base/error.h"

namespace steadylight {
namespace {

/// A file's bytes in memory as OpenEXR's input stream: reading past the end throws, as a
/// truncated file on disk does.
class MemoryStream : public Imf::IStream {
public:
    MemoryStream(std::string_view bytes, const std::string& name) : Imf::IStream(name.c_str()), m_bytes(bytes) {}

    bool read(char c[], int n) override {
        if (n < 0 || m_position > m_bytes.size() || size_t(n) > m_bytes.size() - m_position)
            throw Iex::InputExc("unexpected end of file");
        std::memcpy(c, m_bytes.data() + m_position, size_t(n));
        m_position += size_t(n);
        return m_position < m_bytes.size();
    }
    uint64_t tellg() override { return m_position; }
    void seekg(uint64_t position) override { m_position = position; }

private:
    std::string_view m_bytes;
    uint64_t m_position = 0;
};

}  // namespace

std::vector<std::pair<std::string, int>> exr_layer_channels(const std::string& layer, bool scalar) {
    const std::string prefix = layer.empty() ? "" : layer + ".";
    if (scalar) return {{prefix + "Y", 0}};
    const std::array<std::string, 3> rgb = {"R", "G", "B"};
    std::vector<std::pair<std::string, int>> channels;
    for (int c = 0; c < 3; ++c) channels.emplace_back(prefix + rgb[size_t(c)], c);
    return channels;
}

bool is_exr(std::string_view bytes) { return bytes.size() >= 4 && bytes.substr(0, 4) == "\x76\x2f\x31\x01"; }

Image decode_exr(std::string_view bytes, const std::string& where, const std::string& layer,
                 const ImageSizeCheck& check_size) {
    try {
        MemoryStream stream(bytes, where);
        Imf::InputFile in(stream);
        const Imath::Box2i window = in.header().dataWindow();
        const int64_t width = int64_t(window.max.x) - window.min.x + 1,
                      height = int64_t(window.max.y) - window.min.y + 1;
        if (check_size) check_size(width, height);
        const std::string y_name = (layer.empty() ? "" : layer + ".") + "Y";
        const bool scalar = in.header().channels().findChannel(y_name) != nullptr;
        const auto names = exr_layer_channels(layer, scalar);
        for (const auto& [name, component] : names)
            if (!in.header().channels().findChannel(name)) throw std::runtime_error("no channel " + name);
        // Rows are read a block at a time and appended, so that a header promising more pixels
        // than the file holds fails at the first missing block, before its memory is taken.
        constexpr int64_t block_rows = 64;
        std::vector<std::vector<float>> channels(names.size(), std::vector<float>(size_t(width * block_rows)));
        Image image;
        image.width = int(width);
        for (int64_t y0 = window.min.y; y0 <= window.max.y; y0 += block_rows) {
            const int64_t rows = std::min(block_rows, int64_t(window.max.y) - y0 + 1);
            Imf::FrameBuffer buffer;
            for (size_t c = 0; c < names.size(); ++c)
                buffer.insert(names[c].first,
                              Imf::Slice::Make(Imf::FLOAT, channels[c].data(), Imath::V2i(window.min.x, int(y0)), width,
                                               rows, sizeof(float), sizeof(float) * size_t(width)));
            in.setFrameBuffer(buffer);
            in.readPixels(int(y0), int(y0 + rows - 1));
            for (size_t i = 0; i < size_t(width * rows); ++i)
                image.pixels.push_back(scalar ? Rgb{channels[0][i], channels[0][i], channels[0][i]}
                                              : Rgb{channels[0][i], channels[1][i], channels[2][i]});
            image.height += int(rows);
        }
        return image;
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw InputError(where, std::string("cannot read EXR: ") + e.what());
    }
}

}  // namespace steadylight
