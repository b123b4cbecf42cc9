// Texture sampling (texture.h).
#include "steadylight/scene/texture.h"

#include <cmath>

namespace steadylight {
namespace {

/// Texel index `i` on an axis of `n` texels, wrapped as the sampler says (glTF 2.0 §3.8.4).
int wrap_index(int i, int n, TextureWrap wrap) {
    switch (wrap) {
        case TextureWrap::clamp_to_edge:
            return std::clamp(i, 0, n - 1);
        case TextureWrap::mirrored_repeat: {
            const int m = ((i % (2 * n)) + 2 * n) % (2 * n);
            return m < n ? m : 2 * n - 1 - m;
        }
        case TextureWrap::repeat:
            break;
    }
    return ((i % n) + n) % n;
}

const std::array<float, 256> srgb_table = [] {
    std::array<float, 256> table{};
    for (int i = 0; i < 256; ++i) {
        const double c = i / 255.0;
        table[size_t(i)] = float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
    }
    return table;
}();

Rgba texel(const TextureImage& image, int x, int y, bool srgb) {
    const uint8_t* t = &image.rgba[(size_t(y) * size_t(image.width) + size_t(x)) * 4];
    const auto channel = [&](int c) { return srgb && c < 3 ? srgb_table[t[c]] : float(t[c]) / 255.0f; };
    return {channel(0), channel(1), channel(2), channel(3)};
}

}  // namespace

Vec2 TextureRef::transform(Vec2 uv) const {
    if (rotation == 0 && scale.x == 1 && scale.y == 1 && offset.x == 0 && offset.y == 0) return uv;
    const float c = std::cos(rotation), s = std::sin(rotation);
    const float u = uv.x * scale.x, v = uv.y * scale.y;
    return {c * u + s * v + offset.x, -s * u + c * v + offset.y};
}

float srgb_to_linear(uint8_t v) { return srgb_table[v]; }

Rgba sample_texture(const TextureImage& image, const TextureRef& ref, Vec2 uv, bool srgb) {
    const Vec2 st = ref.transform(uv);
    const float x = st.x * float(image.width), y = st.y * float(image.height);
    if (!std::isfinite(x) || !std::isfinite(y)) return texel(image, 0, 0, srgb);
    if (ref.filter == TextureFilter::nearest)
        return texel(image, wrap_index(int(std::floor(x)), image.width, ref.wrap_s),
                     wrap_index(int(std::floor(y)), image.height, ref.wrap_t), srgb);
    // Bilinear between the four texel centres around (x, y); centres sit at half-integers.
    const float fx = x - 0.5f, fy = y - 0.5f;
    const float x0f = std::floor(fx), y0f = std::floor(fy);
    const float tx = fx - x0f, ty = fy - y0f;
    const int x0 = wrap_index(int(x0f), image.width, ref.wrap_s),
              x1 = wrap_index(int(x0f) + 1, image.width, ref.wrap_s);
    const int y0 = wrap_index(int(y0f), image.height, ref.wrap_t),
              y1 = wrap_index(int(y0f) + 1, image.height, ref.wrap_t);
    const Rgba a = texel(image, x0, y0, srgb), b = texel(image, x1, y0, srgb);
    const Rgba c = texel(image, x0, y1, srgb), d = texel(image, x1, y1, srgb);
    Rgba out;
    for (size_t i = 0; i < 4; ++i)
        out[i] = (a[i] * (1 - tx) + b[i] * tx) * (1 - ty) + (c[i] * (1 - tx) + d[i] * tx) * ty;
    return out;
}

Rgb average_color(const TextureImage& image, bool srgb) {
    double sum[3] = {0, 0, 0};
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const Rgba t = texel(image, x, y, srgb);
            for (size_t c = 0; c < 3; ++c) sum[c] += t[c];
        }
    const double n = std::max(1.0, double(image.width) * double(image.height));
    return {float(sum[0] / n), float(sum[1] / n), float(sum[2] / n)};
}

}  // namespace steadylight
