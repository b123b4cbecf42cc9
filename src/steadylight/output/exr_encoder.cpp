#include "steadylight/output/exr_encoder.h"

#include <Imath/half.h>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "steadylight/base/check.h"
#include "steadylight/output/deflate.h"

namespace steadylight {
namespace {

// The file holds little-endian values, as they are in memory here.
static_assert(std::endian::native == std::endian::little);

/// The largest finite half: above it a half is +inf, which a compositor's blur would spread over
/// the image.
constexpr float max_half = 65504.0f;

/// The lines a ZIP block of an EXR file holds.
constexpr int exr_zip_block_lines = 16;

/// `value` as a half, clamped to +-max_half. A NaN (which render_frame has replaced already,
/// output/frame_layers.h) becomes 0 here too.
half to_finite_half(float value) {
    return std::isnan(value) ? half(0.0f) : half(std::clamp(value, -max_half, max_half));
}

/// `count` values, every `stride`-th float from `floats` (3: one channel of an image's Rgb), as
/// to_finite_half makes them.
void to_finite_halves_one_by_one(const float* floats, size_t stride, half* out, size_t count) {
    for (size_t i = 0; i < count; ++i) out[i] = to_finite_half(floats[stride * i]);
}

#if defined(__x86_64__)
/// The same with the F16C instructions, eight values at a time, in a sixth of the time: the same
/// halves, since both round to the nearest (ties to even), denormals too. A NaN fails the
/// ordered comparison and is masked to +0, as to_finite_half has it.
__attribute__((target("avx,f16c"))) void to_finite_halves_f16c(const float* floats, size_t stride, half* out,
                                                               size_t count) {
    const __m256 lowest = _mm256_set1_ps(-max_half), highest = _mm256_set1_ps(max_half);
    size_t i = 0;
    for (; i + 8 <= count; i += 8) {
        const float* f = floats + stride * i;
        const __m256 v =
            stride == 1 ? _mm256_loadu_ps(f) : _mm256_setr_ps(f[0], f[3], f[6], f[9], f[12], f[15], f[18], f[21]);
        const __m256 is_number = _mm256_cmp_ps(v, v, _CMP_ORD_Q);
        const __m256 finite = _mm256_and_ps(_mm256_min_ps(_mm256_max_ps(v, lowest), highest), is_number);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i),
                         _mm256_cvtps_ph(finite, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC));
    }
    to_finite_halves_one_by_one(floats + stride * i, stride, out + i, count - i);
}
#endif

/// to_finite_halves_one_by_one, with F16C where the processor has it.
void to_finite_halves(const float* floats, size_t stride, half* out, size_t count) {
    static_assert(sizeof(half) == 2);
    SL_CHECK(stride == 1 || stride == 3);
#if defined(__x86_64__)
    static const bool has_f16c = __builtin_cpu_supports("avx") && __builtin_cpu_supports("f16c");
    if (has_f16c) return to_finite_halves_f16c(floats, stride, out, count);
#endif
    to_finite_halves_one_by_one(floats, stride, out, count);
}

/// Appends `value`'s bytes (little-endian, as in memory).
template <class T>
void append_value(std::vector<unsigned char>& out, T value) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    for (const unsigned char byte : bytes) out.push_back(byte);
}

/// The values of an EXR header, appended little-endian.
class HeaderBytes {
public:
    void add_u8(uint8_t value) { m_bytes.push_back(value); }
    void add_i32(int32_t value) { append_value(m_bytes, value); }
    void add_f32(float value) { append_value(m_bytes, value); }
    /// A name: its bytes and a terminating zero.
    void add_name(const std::string& name) {
        m_bytes.insert(m_bytes.end(), name.begin(), name.end());
        m_bytes.push_back(0);
    }
    /// An attribute: its name, its type's name, the size of its value, then the value.
    void add_attribute(const std::string& name, const std::string& type, const HeaderBytes& value) {
        add_name(name);
        add_name(type);
        add_i32(int32_t(value.m_bytes.size()));
        m_bytes.insert(m_bytes.end(), value.m_bytes.begin(), value.m_bytes.end());
    }
    std::vector<unsigned char>& bytes() { return m_bytes; }

private:
    std::vector<unsigned char> m_bytes;
};

// OpenEXR's codes for the values the header names.
constexpr int32_t exr_magic = 20000630;
constexpr int32_t exr_version = 2;
constexpr int32_t exr_long_names = 0x400;  // a name in the header is longer than 31 bytes
constexpr uint8_t exr_zip_compression = 3;
constexpr uint8_t exr_increasing_y = 0;
int32_t exr_pixel_type(ExrPixelType type) { return type == ExrPixelType::half ? 1 : 2; }
constexpr size_t max_name_bytes = 255;
constexpr size_t max_short_name_bytes = 31;

/// The magic number, the version and the header of the file, ending with its zero byte.
std::vector<unsigned char> file_header(int width, int height, const std::vector<ExrChannelValues>& channels,
                                       ExrPixelType type) {
    HeaderBytes out;
    out.add_i32(exr_magic);
    const bool long_names = std::any_of(channels.begin(), channels.end(), [](const ExrChannelValues& channel) {
        return channel.name.size() > max_short_name_bytes;
    });
    out.add_i32(exr_version | (long_names ? exr_long_names : 0));
    HeaderBytes list;
    for (const ExrChannelValues& channel : channels) {
        list.add_name(channel.name);
        list.add_i32(exr_pixel_type(type));
        for (int i = 0; i < 4; ++i) list.add_u8(0);  // not perceptually linear; three reserved bytes
        list.add_i32(1), list.add_i32(1);            // sampled at every pixel in x and y
    }
    list.add_u8(0);
    const auto one_byte = [](uint8_t value) {
        HeaderBytes bytes;
        bytes.add_u8(value);
        return bytes;
    };
    HeaderBytes window;
    for (const int32_t value : {0, 0, width - 1, height - 1}) window.add_i32(value);
    HeaderBytes one, centre;
    one.add_f32(1.0f);
    centre.add_f32(0.0f), centre.add_f32(0.0f);
    // In the order of their names, as OpenEXR writes them.
    out.add_attribute("channels", "chlist", list);
    out.add_attribute("compression", "compression", one_byte(exr_zip_compression));
    out.add_attribute("dataWindow", "box2i", window);
    out.add_attribute("displayWindow", "box2i", window);
    out.add_attribute("lineOrder", "lineOrder", one_byte(exr_increasing_y));
    out.add_attribute("pixelAspectRatio", "float", one);
    out.add_attribute("screenWindowCenter", "v2f", centre);
    out.add_attribute("screenWindowWidth", "float", one);
    out.add_u8(0);
    return std::move(out.bytes());
}

/// Appends to `file` the block of lines [y0, y1): its first line, its size and its bytes, the
/// lines' channels' values deflated after OpenEXR's ZIP predictor, or as they are where that is
/// not shorter.
void append_block(int width, int y0, int y1, const std::vector<ExrChannelValues>& channels, ExrPixelType type,
                  std::vector<unsigned char>& file) {
    const size_t line = size_t(width);
    const size_t value_bytes = type == ExrPixelType::half ? sizeof(half) : sizeof(float);
    const size_t size = size_t(y1 - y0) * channels.size() * line * value_bytes;
    thread_local std::vector<unsigned char> raw, split, predicted;
    raw.resize(size);
    unsigned char* at = raw.data();
    for (int y = y0; y < y1; ++y)
        for (const ExrChannelValues& channel : channels) {
            const size_t stride = size_t(channel.stride);
            const float* values = channel.values + stride * size_t(y) * line;
            if (type == ExrPixelType::half) {
                to_finite_halves(values, stride, reinterpret_cast<half*>(at), line);
            } else {
                for (size_t x = 0; x < line; ++x)
                    std::memcpy(at + x * sizeof(float), values + stride * x, sizeof(float));
            }
            at += line * value_bytes;
        }
    // The even bytes, then the odd ones; then each byte as its difference from the one before,
    // plus 128. Two passes the compiler vectorizes, over plain pointers: through the vectors, a
    // byte stored might be one of a thread_local vector's own pointers, reloaded at every byte.
    split.resize(size);
    predicted.resize(size);
    const unsigned char* const from = raw.data();
    unsigned char* const even_odd = split.data();
    unsigned char* const difference = predicted.data();
    const size_t pairs = size / 2, odd_at = (size + 1) / 2;
    for (size_t j = 0; j < pairs; ++j) even_odd[j] = from[2 * j], even_odd[odd_at + j] = from[2 * j + 1];
    if (size % 2) even_odd[pairs] = from[size - 1];
    difference[0] = even_odd[0];
    for (size_t i = 1; i < size; ++i) difference[i] = static_cast<unsigned char>(even_odd[i] - even_odd[i - 1] + 128);
    append_value(file, int32_t(y0));
    const size_t size_at = file.size();
    append_value(file, int32_t(0));
    if (!append_deflated(predicted.data(), size, size - 1, file)) file.insert(file.end(), raw.begin(), raw.end());
    const int32_t stored = int32_t(file.size() - size_at - sizeof(int32_t));
    std::memcpy(file.data() + size_at, &stored, sizeof stored);
}

}  // namespace

std::vector<unsigned char> encode_exr(int width, int height, std::vector<ExrChannelValues> channels,
                                      ExrPixelType type) {
    SL_CHECK(width > 0 && height > 0 && !channels.empty());
    std::sort(channels.begin(), channels.end(),
              [](const ExrChannelValues& a, const ExrChannelValues& b) { return a.name < b.name; });
    for (size_t i = 0; i < channels.size(); ++i) {
        SL_CHECK(!channels[i].name.empty() && channels[i].name.size() <= max_name_bytes);
        SL_CHECK(i == 0 || channels[i].name != channels[i - 1].name);
    }
    // The header, the offset of every block in the file, then the blocks, each its first line,
    // its size and its bytes; one block after another, on the calling thread: a frame is
    // written beside the next one's rendering, which keeps every core busy, and a write once
    // begun must finish (the parallel loops of base/parallel.h stop at an interrupt).
    std::vector<unsigned char> file = file_header(width, height, channels, type);
    const size_t offsets_at = file.size();
    file.resize(offsets_at + size_t((height + exr_zip_block_lines - 1) / exr_zip_block_lines) * sizeof(uint64_t));
    for (int y0 = 0; y0 < height; y0 += exr_zip_block_lines) {
        const uint64_t offset = file.size();
        std::memcpy(file.data() + offsets_at + size_t(y0 / exr_zip_block_lines) * sizeof(uint64_t), &offset,
                    sizeof offset);
        append_block(width, y0, std::min(y0 + exr_zip_block_lines, height), channels, type, file);
    }
    return file;
}

}  // namespace steadylight
