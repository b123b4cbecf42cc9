// Linear RGB radiometric quantities (radiance, reflectance, power), one float per channel.
#pragma once

#include <algorithm>
#include <cmath>

namespace steadylight {

struct Rgb {
    float r = 0, g = 0, b = 0;

    constexpr Rgb& operator+=(Rgb o) {
        r += o.r;
        g += o.g;
        b += o.b;
        return *this;
    }
    constexpr Rgb& operator*=(Rgb o) {
        r *= o.r;
        g *= o.g;
        b *= o.b;
        return *this;
    }
    constexpr Rgb& operator*=(float s) {
        r *= s;
        g *= s;
        b *= s;
        return *this;
    }
    constexpr float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
    constexpr bool operator==(const Rgb&) const = default;
};

constexpr Rgb operator+(Rgb a, Rgb b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
constexpr Rgb operator-(Rgb a, Rgb b) { return {a.r - b.r, a.g - b.g, a.b - b.b}; }
constexpr Rgb operator*(Rgb a, Rgb b) { return {a.r * b.r, a.g * b.g, a.b * b.b}; }
constexpr Rgb operator*(Rgb a, float s) { return {a.r * s, a.g * s, a.b * s}; }
constexpr Rgb operator*(float s, Rgb a) { return a * s; }
constexpr Rgb operator/(Rgb a, float s) { return a * (1.0f / s); }

constexpr float max_component(Rgb c) { return std::max({c.r, c.g, c.b}); }
constexpr float average(Rgb c) { return (c.r + c.g + c.b) / 3.0f; }
/// Rec. 709 luminance of linear RGB.
constexpr float luminance(Rgb c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }
constexpr bool is_black(Rgb c) { return c.r == 0 && c.g == 0 && c.b == 0; }
inline bool is_finite(Rgb c) { return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b); }

}  // namespace steadylight
