// The view transform for 8-bit outputs (view_transform.h).
#include "steadylight/output/view_transform.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include "steadylight/base/error.h"
#include "steadylight/base/rng.h"

namespace steadylight {
namespace {

/// Hable's curve before normalisation, with the constants of his GDC 2010 talk: shoulder
/// strength A, linear strength B, linear angle C, toe strength D, toe numerator E, toe
/// denominator F. f(0) = DE/DF - E/F = 0.
float hable(float x) {
    constexpr float A = 0.15f, B = 0.50f, C = 0.10f, D = 0.20f, E = 0.02f, F = 0.30f;
    return (x * (A * x + C * B) + D * E) / (x * (A * x + B) + D * F) - E / F;
}

constexpr float hable_exposure_bias = 2.0f;  // from the talk's sample code
constexpr float hable_white = 11.2f;         // linear white point W of the talk

/// The dither's hash of pixel (x, y), channel c is hash_ids(x, y, c, dither_key): the pixels of
/// a column share its first step, hash_more(0, x), and a pixel's channels their first two.
constexpr uint64_t dither_key = 0x5344495448ull;

/// A fixed dither offset in [-0.5, 0.5) of one code value for channel c of the pixel whose hash
/// of x and y is `pixel`.
constexpr float dither_offset(uint64_t pixel, int c) {
    const uint64_t h = hash_more(hash_more(pixel, uint64_t(c)), dither_key);
    return float(h >> 40) / float(1 << 24) - 0.5f;
}
static_assert(dither_offset(hash_more(hash_more(0, 3), 5), 1) ==
              float(hash_ids(3, 5, 1, dither_key) >> 40) / float(1 << 24) - 0.5f);

/// The sRGB curve above its linear toe (values in (0.0031308, 1], which lie in the binary
/// octaves from 2^-9 up), tabulated at 2^srgb_steps_bits points an octave, evenly spaced in the
/// float's mantissa, and interpolated between them: within 1e-7 of the curve (a step is a
/// thousandth of the value, over which the curve departs from its chord by a millionth of it).
/// std::pow took two fifths of a frame's PNG encoding; a table read and a multiply-add do not.
constexpr int srgb_steps_bits = 10, srgb_first_octave = -9;
constexpr int srgb_octaves = -srgb_first_octave, srgb_shift = 23 - srgb_steps_bits;

struct SrgbTable {
    std::array<float, (srgb_octaves << srgb_steps_bits) + 1> values;
    SrgbTable() {
        for (size_t i = 0; i < values.size(); ++i) {
            const double v = std::ldexp(1.0 + double(i % (1 << srgb_steps_bits)) / (1 << srgb_steps_bits),
                                        srgb_first_octave + int(i >> srgb_steps_bits));
            values[i] = float(1.055 * std::pow(v, 1 / 2.4) - 0.055);
        }
    }
};
// Built once at start-up, not on first use: a function's static would be checked at every value.
const SrgbTable srgb_table;

float srgb_above_toe(float v) {
    constexpr uint32_t first = uint32_t(127 + srgb_first_octave) << 23;  // the bits of 2^srgb_first_octave
    const uint32_t bits = std::bit_cast<uint32_t>(v) - first;
    const uint32_t step = bits >> srgb_shift;
    const float t = float(bits & ((1u << srgb_shift) - 1)) * (1.0f / (1u << srgb_shift));
    const float below = srgb_table.values[step];
    return t == 0 ? below : below + t * (srgb_table.values[step + 1] - below);
}

}  // namespace

ViewCurve parse_view_curve(const std::string& name, const std::string& option) {
    if (name == "standard") return ViewCurve::standard;
    if (name == "filmic") return ViewCurve::filmic;
    throw InputError(option, "unknown view transform \"" + name + "\" (standard or filmic)");
}

float apply_exposure(float v, float exposure_ev) { return v * std::exp2(exposure_ev); }

float filmic_curve(float v) {
    static const float white_scale = 1 / hable(hable_white);
    if (!(v > 0)) return 0;  // also NaN
    if (v > 1e6f) return 1;  // also infinity, where the rational function gives inf/inf
    return std::min(1.0f, hable(hable_exposure_bias * std::max(v, 0.0f)) * white_scale);
}

float apply_view_curve(float v, ViewCurve curve) {
    if (curve == ViewCurve::filmic) return filmic_curve(v);
    return std::clamp(v, 0.0f, 1.0f);
}

float linear_to_srgb(float v) {
    v = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
    return v <= 0.0031308f ? 12.92f * v : srgb_above_toe(v);
}

std::vector<unsigned char> encode_srgb8(const Image& image, const ViewTransform& transform, const Image* alpha) {
    const size_t channels = alpha ? 4 : 3;
    std::vector<unsigned char> bytes(image.pixels.size() * channels);
    // std::lround of a float, halves away from zero, in double arithmetic, where adding the half
    // is exact, clamped to [0, 255]: over [0, 255] the conversion's truncation is the floor, and
    // no libm call is made per value (std::floor is one without SSE4.1).
    const auto to_byte = [](float code) {
        return static_cast<unsigned char>(std::clamp(double(code) + 0.5, 0.0, 255.0));
    };
    // apply_exposure's factor, once: the same products.
    const float exposure = std::exp2(transform.exposure_ev);
    std::vector<uint64_t> dither_columns(size_t(image.width));
    for (int x = 0; x < image.width; ++x) dither_columns[size_t(x)] = hash_more(0, uint64_t(x));
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const size_t pixel = (size_t(y) * size_t(image.width) + size_t(x)) * channels;
            const uint64_t dither_at = hash_more(dither_columns[size_t(x)], uint64_t(y));
            Rgb colour = image.at(x, y);
            if (alpha) {
                const float a = std::clamp(alpha->at(x, y).r, 0.0f, 1.0f);
                colour = a > 0 ? colour / a : Rgb{};
                bytes[pixel + 3] = to_byte(255 * a);
            }
            for (int c = 0; c < 3; ++c) {
                const float linear = colour[c] * exposure;
                float code = 255 * linear_to_srgb(apply_view_curve(linear, transform.curve));
                if (transform.dither) code += dither_offset(dither_at, c);
                bytes[pixel + size_t(c)] = to_byte(code);
            }
        }
    return bytes;
}

}  // namespace steadylight
