#include "steadylight/scene/radiance_hdr.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <vector>

#include "steadylight/base/error.h"

namespace steadylight {
namespace {

/// The widths Radiance writes run-length encoded scanlines for (the width fits in 15 bits).
bool run_length_width(int64_t width) { return width >= 8 && width <= 0x7fff; }

struct HdrLayout {
    int64_t width = 0, height = 0;
    size_t pixels_start = 0;  // the offset of the first scanline
};

/// The next line from `at` (without its newline and a carriage return before it), moving `at`
/// past it; nothing when no newline ends it.
std::optional<std::string_view> next_line(std::string_view bytes, size_t& at) {
    const size_t newline = bytes.find('\n', at);
    if (newline == std::string_view::npos) return std::nullopt;
    std::string_view line = bytes.substr(at, newline - at);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    at = newline + 1;
    return line;
}

/// A positive decimal number of at most 9 digits from the start of `text`, moving past it.
std::optional<int64_t> take_size(std::string_view& text) {
    size_t digits = 0;
    while (digits < text.size() && text[digits] >= '0' && text[digits] <= '9') ++digits;
    if (digits == 0 || digits > 9) return std::nullopt;
    int64_t value = 0;
    for (size_t i = 0; i < digits; ++i) value = value * 10 + (text[i] - '0');
    text.remove_prefix(digits);
    return value > 0 ? std::optional(value) : std::nullopt;
}

HdrLayout read_header(std::string_view bytes, const std::string& where) {
    const auto refuse = [&](const std::string& why) {
        throw InputError(where, "not a Radiance HDR image (" + why + ")");
    };
    size_t at = 0;
    next_line(bytes, at);  // "#?" and the name of the program that wrote it
    for (;;) {
        const std::optional<std::string_view> line = next_line(bytes, at);
        if (!line) refuse("its header has no end");
        if (line->empty()) break;
        if (line->starts_with("FORMAT=") && line->substr(7) != "32-bit_rle_rgbe")
            refuse(fmt::format("{}: only 32-bit_rle_rgbe, RGB with a shared exponent, is read",
                               line->substr(0, std::min<size_t>(line->size(), 60))));
    }
    const std::optional<std::string_view> resolution = next_line(bytes, at);
    if (!resolution) refuse("no resolution line after the header");
    std::string_view text = *resolution;
    const auto orientation_problem = [&] {
        return fmt::format("its resolution line \"{}\" is not \"-Y height +X width\", the orientation read",
                           resolution->substr(0, std::min<size_t>(resolution->size(), 40)));
    };
    if (!text.starts_with("-Y ")) refuse(orientation_problem());
    text.remove_prefix(3);
    const std::optional<int64_t> height = take_size(text);
    if (!height || !text.starts_with(" +X ")) refuse(orientation_problem());
    text.remove_prefix(4);
    const std::optional<int64_t> width = take_size(text);
    if (!width || !text.empty()) refuse(orientation_problem());
    return {*width, *height, at};
}

/// ((r, g, b) + 0.5) 2^(e - 136): the middle of the interval of values a byte stands for.
Rgb rgbe_to_rgb(const unsigned char* rgbe) {
    if (rgbe[3] == 0) return {};
    const float scale = std::ldexp(1.0f, int(rgbe[3]) - 136);
    return {(rgbe[0] + 0.5f) * scale, (rgbe[1] + 0.5f) * scale, (rgbe[2] + 0.5f) * scale};
}

/// Decodes the scanlines of `layout` from `bytes` into `image`.
class ScanlineReader {
public:
    ScanlineReader(std::string_view bytes, const std::string& where, const HdrLayout& layout)
        : m_bytes(bytes), m_where(where), m_at(layout.pixels_start), m_width(layout.width) {}

    /// Row `y` as RGBE bytes, 4 per pixel.
    void read_row(int64_t y, std::vector<unsigned char>& rgbe) {
        m_row = y;
        if (run_length_width(m_width) && left() >= 4 && byte(0) == 2 && byte(1) == 2 && byte(2) < 0x80) {
            const int64_t encoded_width = int64_t(byte(2)) << 8 | byte(3);
            if (encoded_width != m_width)
                damaged(fmt::format("its scanline says {} pixels, not {}", encoded_width, m_width));
            m_at += 4;
            for (size_t component = 0; component < 4; ++component) read_runs(rgbe, component);
            return;
        }
        need(4 * size_t(m_width));
        std::memcpy(rgbe.data(), m_bytes.data() + m_at, 4 * size_t(m_width));
        m_at += 4 * size_t(m_width);
    }

private:
    size_t left() const { return m_bytes.size() - m_at; }
    unsigned char byte(size_t offset) const { return static_cast<unsigned char>(m_bytes[m_at + offset]); }
    [[noreturn]] void damaged(const std::string& why) const {
        throw InputError(m_where, fmt::format("a damaged Radiance HDR image (row {}: {})", m_row, why));
    }
    void need(size_t count) const {
        if (left() < count) damaged("the file ends inside it");
    }

    /// One component of a run-length encoded scanline: runs of one byte repeated (a count above
    /// 128) and of bytes as they are (a count from 1 to 128).
    void read_runs(std::vector<unsigned char>& rgbe, size_t component) {
        int64_t x = 0;
        while (x < m_width) {
            need(1);
            const int count = byte(0);
            const bool repeated = count > 128;
            const int64_t length = repeated ? count - 128 : count;
            if (length == 0) damaged("a run of length zero");
            if (length > m_width - x) damaged("a run past the end of the scanline");
            need(1 + size_t(repeated ? 1 : length));
            for (int64_t i = 0; i < length; ++i)
                rgbe[size_t(x + i) * 4 + component] = byte(repeated ? 1 : 1 + size_t(i));
            m_at += 1 + size_t(repeated ? 1 : length);
            x += length;
        }
    }

    std::string_view m_bytes;
    const std::string& m_where;
    size_t m_at;
    int64_t m_width;
    int64_t m_row = 0;
};

/// The fewest bytes a scanline of `width` pixels can take: runs of 127 in each component (2 bytes
/// each) after a 4-byte start, or 4 bytes a pixel where scanlines are not run-length encoded.
int64_t fewest_scanline_bytes(int64_t width) {
    return run_length_width(width) ? 4 + 4 * 2 * ((width + 126) / 127) : 4 * width;
}

}  // namespace

bool is_radiance_hdr(std::string_view bytes) { return bytes.starts_with("#?"); }

Image decode_radiance_hdr(std::string_view bytes, const std::string& where, const ImageSizeCheck& check_size) {
    if (!is_radiance_hdr(bytes)) throw InputError(where, "not a Radiance HDR image (it does not begin with #?)");
    const HdrLayout layout = read_header(bytes, where);
    if (check_size) check_size(layout.width, layout.height);
    // Before any memory is taken: a header may promise more rows than the bytes can hold.
    if (int64_t(bytes.size() - layout.pixels_start) / layout.height < fewest_scanline_bytes(layout.width))
        throw InputError(where, fmt::format("a damaged Radiance HDR image ({} bytes of pixels cannot hold {} x {})",
                                            bytes.size() - layout.pixels_start, layout.width, layout.height));
    Image image(int(layout.width), int(layout.height));
    std::vector<unsigned char> rgbe(4 * size_t(layout.width));
    ScanlineReader reader(bytes, where, layout);
    for (int y = 0; y < image.height; ++y) {
        reader.read_row(y, rgbe);
        for (int x = 0; x < image.width; ++x) image.at(x, y) = rgbe_to_rgb(rgbe.data() + 4 * size_t(x));
    }
    return image;
}

}  // namespace steadylight
