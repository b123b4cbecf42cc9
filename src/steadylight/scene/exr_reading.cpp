#include "steadylight/scene/exr_reading.h"

#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <fmt/format.h>
#include <openexr.h>

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

/// Tiles may be larger than the image they hold (a small image in the usual 64 x 64 tiles), but
/// not larger on a side than this or the image.
constexpr int64_t max_tile_side = 1024;

/// `text` safe to print: at most 200 characters, other than printable ASCII shown as '?' (the
/// library's messages quote bytes of the file).
std::string printable(std::string_view text) {
    std::string shown(text.substr(0, 200));
    for (char& c : shown)
        if (c < 0x20 || c > 0x7e) c = '?';
    return shown;
}

/// The headers of an EXR file as OpenEXRCore, the library's newer C reader, reads them: it checks
/// every attribute against the file's size before it takes memory, which the C++ reader does
/// not (an attribute stated as 800 MB in a 3 kB file was allocated first), and it gives each
/// part's data window before the C++ reader allocates line buffers and offset tables by it (a
/// window 33 million pixels wide in a 260-byte file). Both took over a second under
/// AddressSanitizer; found by fuzzing.
class CoreHeaders {
public:
    CoreHeaders(std::string_view bytes, const std::string& where) : m_bytes(bytes) {
        exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
        init.user_data = this;
        init.read_fn = read;
        init.size_fn = size;
        init.error_handler_fn = keep_error;
        init.flags = EXR_CONTEXT_FLAG_STRICT_HEADER;
        const exr_result_t result = exr_start_read(&m_context, where.c_str(), &init);
        if (result == EXR_ERR_SUCCESS) return;
        m_context = nullptr;
        if (m_problem.empty()) m_problem = exr_get_default_error_message(result);
    }
    ~CoreHeaders() {
        if (m_context) exr_finish(&m_context);
    }
    CoreHeaders(const CoreHeaders&) = delete;
    CoreHeaders& operator=(const CoreHeaders&) = delete;

    /// Why the headers could not be read, or "" when they could.
    const std::string& problem() const { return m_problem; }
    /// The size of a part's data window, and of its tiles (0 x 0 for scanlines).
    struct Part {
        int64_t width = 0, height = 0;
        int64_t tile_width = 0, tile_height = 0;
    };
    std::vector<Part> parts() const {
        std::vector<Part> parts;
        int count = 0;
        if (!m_context || exr_get_count(m_context, &count) != EXR_ERR_SUCCESS) return parts;
        for (int index = 0; index < count; ++index) {
            exr_attr_box2i_t window{};
            if (exr_get_data_window(m_context, index, &window) != EXR_ERR_SUCCESS) continue;
            Part& part = parts.emplace_back();
            part.width = int64_t(window.max.x) - window.min.x + 1;
            part.height = int64_t(window.max.y) - window.min.y + 1;
            uint32_t tile_width = 0, tile_height = 0;
            exr_tile_level_mode_t levels{};
            exr_tile_round_mode_t rounding{};
            if (exr_get_tile_descriptor(m_context, index, &tile_width, &tile_height, &levels, &rounding) ==
                EXR_ERR_SUCCESS) {
                part.tile_width = tile_width;
                part.tile_height = tile_height;
            }
        }
        return parts;
    }

private:
    static int64_t read(exr_const_context_t, void* self, void* buffer, uint64_t count, uint64_t offset,
                        exr_stream_error_func_ptr_t) {
        const std::string_view bytes = static_cast<CoreHeaders*>(self)->m_bytes;
        if (offset >= bytes.size()) return 0;
        const size_t n = std::min<size_t>(count, bytes.size() - offset);
        std::memcpy(buffer, bytes.data() + offset, n);
        return int64_t(n);
    }
    static int64_t size(exr_const_context_t, void* self) {
        return int64_t(static_cast<CoreHeaders*>(self)->m_bytes.size());
    }
    /// Keeps the first message (called without a context when there is none yet: the
    /// constructor then takes the message of the result instead).
    static void keep_error(exr_const_context_t context, exr_result_t, const char* message) {
        void* self = nullptr;
        if (!context || exr_get_user_data(context, &self) != EXR_ERR_SUCCESS || !self || !message) return;
        std::string& problem = static_cast<CoreHeaders*>(self)->m_problem;
        if (problem.empty()) problem = printable(message);
    }

    std::string_view m_bytes;
    exr_context_t m_context = nullptr;
    std::string m_problem;
};

}  // namespace

std::vector<std::pair<std::string, int>> exr_layer_channels(const std::string& layer, bool scalar,
                                                            const std::string& scalar_channel) {
    const std::string prefix = layer.empty() ? "" : layer + ".";
    if (scalar) return {{prefix + scalar_channel, 0}};
    const std::array<std::string, 3> rgb = {"R", "G", "B"};
    std::vector<std::pair<std::string, int>> channels;
    for (int c = 0; c < 3; ++c) channels.emplace_back(prefix + rgb[size_t(c)], c);
    return channels;
}

bool is_exr(std::string_view bytes) { return bytes.size() >= 4 && bytes.substr(0, 4) == "\x76\x2f\x31\x01"; }

Image decode_exr(std::string_view bytes, const std::string& where, const std::string& layer,
                 const ImageSizeCheck& check_size) {
    {
        const CoreHeaders headers(bytes, where);
        if (!headers.problem().empty()) throw InputError(where, "cannot read EXR: " + headers.problem());
        for (const CoreHeaders::Part& part : headers.parts()) {
            if (check_size) check_size(part.width, part.height);
            // The C++ reader allocates a tile's pixels for each of its threads: a tile far larger
            // than the image (262144 x 1024 for 16 x 8, 2.4 GB; found by fuzzing) is damage.
            if (part.tile_width > std::max<int64_t>(part.width, max_tile_side) ||
                part.tile_height > std::max<int64_t>(part.height, max_tile_side))
                throw InputError(where,
                                 fmt::format("a damaged EXR image (tiles of {} x {} pixels in an image of {} x {})",
                                             part.tile_width, part.tile_height, part.width, part.height));
        }
    }
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
