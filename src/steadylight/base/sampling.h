// Warping uniform samples in [0,1)^2 onto the domains the renderer integrates over, each with
// its pdf. Every sample_* has a matching *_pdf, checked against each other in sampling_test.cpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

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

/// Uniform direction in the cone of half-angle acos(cos_max) around +z. pdf = uniform_cone_pdf.
inline Vec3 sample_uniform_cone(Vec2 u, float cos_max) {
    const float cos_theta = 1 - u.x * (1 - cos_max);
    const float sin_theta = std::sqrt(std::max(0.0f, 1 - cos_theta * cos_theta));
    const float phi = 2 * pi * u.y;
    return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}
inline float uniform_cone_pdf(float cos_max) { return 1 / (2 * pi * (1 - cos_max)); }

/// Uniform barycentrics (b1, b2) on a triangle; the third is 1 - b1 - b2.
inline Vec2 sample_uniform_triangle(Vec2 u) {
    const float su = std::sqrt(u.x);
    return {1 - su, u.y * su};
}

/// Sample `index` of `count` stratified points in [0,1)^2: a Hammersley set (x stratified by the
/// index, y by its base-2 radical inverse) shifted by `shift` modulo 1 (Cranley-Patterson), so
/// each pixel gets its own well-spread set. Used for pixel positions (anti-aliasing).
inline Vec2 stratified_2d(uint32_t index, uint32_t count, Vec2 shift) {
    uint32_t bits = index;
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    const float x = (float(index) + 0.5f) / float(count) + shift.x;
    const float y = float(bits) * 0x1p-32f + shift.y;
    return {std::min(x - std::floor(x), 0x1.fffffep-1f), std::min(y - std::floor(y), 0x1.fffffep-1f)};
}

/// A permutation of [0, count) chosen by `seed`: index i's place (Kensler 2013, "Correlated
/// Multi-Jittered Sampling", its hash permutation, walking the cycle until it lands inside).
inline uint32_t permuted_index(uint32_t i, uint32_t count, uint32_t seed) {
    uint32_t w = count - 1;
    w |= w >> 1, w |= w >> 2, w |= w >> 4, w |= w >> 8, w |= w >> 16;
    do {
        i ^= seed, i *= 0xe170893du, i ^= seed >> 16, i ^= (i & w) >> 4, i ^= seed >> 8, i *= 0x0929eb3fu;
        i ^= seed >> 23, i ^= (i & w) >> 1, i *= 1 | seed >> 27, i *= 0x6935fa69u, i ^= (i & w) >> 11;
        i *= 0x74dcb303u, i ^= (i & w) >> 2, i *= 0x9e501cc3u, i ^= (i & w) >> 2, i *= 0xc860a3dfu;
        i &= w, i ^= i >> 5;
    } while (i >= count);
    return (i + seed) % count;
}

/// Power heuristic with beta = 2 (Veach 1997) for one sample from each of two strategies.
inline float power_heuristic(float pdf_a, float pdf_b) {
    const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    return a + b > 0 ? a / (a + b) : 0.0f;
}

}  // namespace steadylight
