// Warping uniform samples in [0,1)^2 onto the domains the renderer integrates over, each with
// its pdf. Every sample_* has a matching *_pdf, checked against each other in sampling_test.cpp.
#pragma once

#include <algorithm>
#include <cmath>

#include "steadylight/base/vec.h"

namespace steadylight {

/// Cosine-weighted direction on the hemisphere around +z (Malley's method). pdf = cos/pi.
inline Vec3 sample_cosine_hemisphere(Vec2 u) {
    const float r = std::sqrt(u.x);
    const float phi = 2 * pi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1 - u.x))};
}
inline float cosine_hemisphere_pdf(float cos_theta) { return std::max(0.0f, cos_theta) * inv_pi; }

/// Uniform direction on the unit sphere. pdf = 1 / (4 pi).
inline Vec3 sample_uniform_sphere(Vec2 u) {
    const float z = 1 - 2 * u.x;
    const float r = std::sqrt(std::max(0.0f, 1 - z * z));
    const float phi = 2 * pi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
constexpr float uniform_sphere_pdf() { return 1 / (4 * pi); }

/// Uniform barycentrics (b1, b2) on a triangle; the third is 1 - b1 - b2.
inline Vec2 sample_uniform_triangle(Vec2 u) {
    const float su = std::sqrt(u.x);
    return {1 - su, u.y * su};
}

/// Power heuristic with beta = 2 (Veach 1997) for one sample from each of two strategies.
inline float power_heuristic(float pdf_a, float pdf_b) {
    const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    return a + b > 0 ? a / (a + b) : 0.0f;
}

}  // namespace steadylight
