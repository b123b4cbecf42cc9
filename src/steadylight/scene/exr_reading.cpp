#include "steadylight/scene/exr_reading.h"

#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <fmt/format.h>

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

/// A little-endian 32-bit integer at `at` (4 bytes there).
uint32_t read_u32(std::string_view bytes, size_t at) {
    uint32_t value = 0;
    for (size_t i = 0; i < 4; ++i) value |= uint32_t(static_cast<unsigned char>(bytes[at + i])) << (8 * i);
    return value;
}

/// `text` shown safely in a message: at most 40 characters, others than printable ASCII as '?'.
std::string printable(std::string_view text) {
    std::string shown(text.substr(0, 40));
    for (char& c : shown)
        if (c < 0x20 || c > 0x7e) c = '?';
    return shown;
}

/// What a walk over an EXR file's headers finds before OpenEXR reads them.
struct ExrHeaders {
    /// Why the headers cannot all be in the file, or "" when every attribute lies inside it:
    /// OpenEXR allocates an attribute's stated size (up to 2 GB) before it finds the bytes
    /// missing (a 3 kB file took over a second under AddressSanitizer; found by fuzzing).
    std::string problem;
    /// The size of each part's data window: OpenEXR allocates line buffers and offset tables by
    /// it as it opens the file, before the caller could refuse it (a 260-byte file stating a
    /// window 33 million pixels wide; found by fuzzing).
    std::vector<std::pair<int64_t, int64_t>> window_sizes;
};

/// A header is a list of attributes (name, type name, 32-bit size, value) ended by an empty name;
/// a multi-part file has several, ended by an empty header.
ExrHeaders walk_headers(std::string_view bytes) {
    constexpr uint32_t multipart_flag = 0x1000;
    const std::string cut = "a damaged EXR image (the file ends inside its header)";
    if (bytes.size() < 8) return {cut};
    const bool multipart = (read_u32(bytes, 4) & multipart_flag) != 0;
    size_t at = 8;
    const auto take_name = [&](std::string_view& name) {
        const size_t end = bytes.find('\0', at);
        if (end == std::string_view::npos) return false;
        name = bytes.substr(at, end - at);
        at = end + 1;
        return true;
    };
    ExrHeaders headers;
    for (;;) {
        int attributes = 0;
        for (std::string_view name, type;; ++attributes) {
            if (!take_name(name)) return {cut};
            if (name.empty()) break;
            if (!take_name(type) || bytes.size() - at < 4) return {cut};
            const uint32_t size = read_u32(bytes, at);
            at += 4;
            if (size > bytes.size() - at)
                return {
                    fmt::format("a damaged EXR image (its attribute \"{}\" of {} bytes runs past the end of the "
                                "file)",
                                printable(name), size)};
            if (name == "dataWindow" && type == "box2i" && size == 16) {
                const auto corner = [&](size_t i) { return int64_t(int32_t(read_u32(bytes, at + 4 * i))); };
                headers.window_sizes.emplace_back(corner(2) - corner(0) + 1, corner(3) - corner(1) + 1);
            }
            at += size;
        }
        if (!multipart || attributes == 0) return headers;
    }
}

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
    const ExrHeaders headers = walk_headers(bytes);
    if (!headers.problem.empty()) throw InputError(where, headers.problem);
    if (check_size)
        for (const auto& [width, height] : headers.window_sizes)
            if (width > 0 && height > 0) check_size(width, height);
    try {
        MemoryStream stream(bytes, where);
        Imf::InputFile in(stream);
        const Imath::Box2i window = in.header().dataWindow();
        const int64_t width = int64_t(window.max.x) - window.min.x + 1,
                      height = int64_t(window.max.y) - window.min.y + 1;
        if (check_size) check_size(width, height);  // again, on the window OpenEXR read
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
