#include "steadylight/scene/environment_map.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "steadylight/base/check.h"
#include "steadylight/base/hash.h"
#include "steadylight/base/sampling.h"

namespace steadylight {
namespace {

/// The floor added to every pixel's luminance in the sampling weights, as a share of the image's
/// mean luminance. A direction with radiance > 0 must have pdf > 0: an estimator that samples
/// only the light (photon emission; direct light where the BSDF cannot be sampled) would
/// otherwise never see it and lose its light, and MIS is unbiased only where some strategy can
/// produce the direction. Luminance alone can be 0 where radiance is not (a component so small
/// that luminance's weighted sum underflows). The floor is uniform in solid angle and costs at
/// most its share of the samples, spent on dark directions.
constexpr float luminance_floor_share = 1e-3f;

/// sin θ at the centre of row j of `height` rows from θ = 0 (the top, +y) to θ = π.
float row_sin_theta(int j, int height) { return std::sin(pi * (float(j) + 0.5f) / float(height)); }

/// The solid angle of a pixel in row j: (2π / width) (cos θ_top - cos θ_bottom).
double pixel_solid_angle(int j, int width, int height) {
    const double top = std::acos(-1.0) * j / height, bottom = std::acos(-1.0) * (j + 1) / height;
    return 2 * std::acos(-1.0) / width * (std::cos(top) - std::cos(bottom));
}

}  // namespace

EnvironmentMap::EnvironmentMap(Rgb radiance)
    : m_radiance(radiance), m_mean_luminance(luminance(radiance)), m_black(steadylight::is_black(radiance)) {
    SL_CHECK(is_finite(radiance) && radiance.r >= 0 && radiance.g >= 0 && radiance.b >= 0);
}

EnvironmentMap::EnvironmentMap(Image image, float strength, float rotation_degrees)
    : m_image(std::move(image)), m_strength(strength), m_rotation_degrees(rotation_degrees) {
    SL_CHECK(m_image.width > 0 && m_image.height > 0 &&
             m_image.pixels.size() == size_t(m_image.width) * size_t(m_image.height));
    SL_CHECK(std::isfinite(strength) && strength >= 0 && std::isfinite(rotation_degrees));
    const float a = rotation_degrees * pi / 180;
    m_cos_rotation = std::cos(a);
    m_sin_rotation = std::sin(a);
    const int width = m_image.width, height = m_image.height;
    // The mean luminance, each pixel weighted by its exact solid angle.
    double weighted = 0;
    m_black = true;
    for (int j = 0; j < height; ++j) {
        double row = 0;
        for (int i = 0; i < width; ++i) {
            const Rgb& p = m_image.at(i, j);
            SL_CHECK(is_finite(p) && p.r >= 0 && p.g >= 0 && p.b >= 0);
            row += luminance(p);
            m_black = m_black && steadylight::is_black(p);
        }
        weighted += row * pixel_solid_angle(j, width, height);
    }
    m_black = m_black || strength == 0;
    const double mean_pixel_luminance = weighted / (4 * std::acos(-1.0));
    m_mean_luminance = float(mean_pixel_luminance * strength);
    // Sampling weights: luminance (plus the floor) times the pixel's solid angle, which is
    // proportional to sin θ at its centre; over the brightest pixel's luminance, so that neither
    // the floor nor the weights' sums leave the range of floats whatever the image's scale.
    double brightest = 0;
    for (const Rgb& p : m_image.pixels) brightest = std::max(brightest, double(luminance(p)));
    const double scale = brightest > 0 ? 1 / brightest : 1;
    const double floor = luminance_floor_share * mean_pixel_luminance;
    std::vector<float> weights(m_image.pixels.size());
    for (int j = 0; j < height; ++j) {
        const double sin_theta = row_sin_theta(j, height);
        for (int i = 0; i < width; ++i)
            weights[size_t(j) * size_t(width) + size_t(i)] =
                float((luminance(m_image.at(i, j)) + floor) * scale * sin_theta);
    }
    m_distribution = Distribution2D(weights, width, height);
}

EnvironmentMap::ImagePoint EnvironmentMap::image_point(Vec3 w) const {
    // Turned about +y into the image's frame.
    const float x = w.x * m_cos_rotation + w.z * m_sin_rotation, z = -w.x * m_sin_rotation + w.z * m_cos_rotation;
    const float r = std::sqrt(x * x + z * z);
    // u = atan2(z, x) / 2π + ½; 1 - v = θ / π with θ = acos(y), from atan2 for accuracy near the poles.
    const Vec2 uv = {std::atan2(z, x) * (0.5f * inv_pi) + 0.5f, std::atan2(r, w.y) * inv_pi};
    return {uv, r / std::sqrt(r * r + w.y * w.y)};
}

Rgb EnvironmentMap::radiance(Vec3 w) const {
    if (m_image.pixels.empty()) return m_radiance;
    const Distribution2D::Cell cell = m_distribution.cell(image_point(w).uv);
    return m_image.at(cell.column, cell.row) * m_strength;
}

float EnvironmentMap::pdf(Vec3 w) const {
    if (m_black) return 0;
    if (m_image.pixels.empty()) return uniform_sphere_pdf();
    const ImagePoint point = image_point(w);
    // dω = sin θ dθ dφ = 2π² sin θ du dv.
    if (!(point.sin_theta > 0)) return 0;
    return m_distribution.pdf(point.uv) / (2 * pi * pi * point.sin_theta);
}

std::optional<EnvironmentMap::Sample> EnvironmentMap::sample(Vec2 u) const {
    if (m_black) return std::nullopt;
    Vec3 w;
    if (m_image.pixels.empty()) {
        w = sample_uniform_sphere(u);
    } else {
        const Vec2 uv = m_distribution.sample(u).uv;
        const float theta = pi * uv.y, phi = 2 * pi * (uv.x - 0.5f);
        const float sin_theta = std::sin(theta);
        const float x = sin_theta * std::cos(phi), z = sin_theta * std::sin(phi);
        // Back from the image's frame: the inverse of image_point's rotation.
        w = {x * m_cos_rotation - z * m_sin_rotation, std::cos(theta), x * m_sin_rotation + z * m_cos_rotation};
    }
    // From w itself, so that the sample agrees bit for bit with pdf(w) and radiance(w) (MIS
    // weights computed either way match).
    const float density = pdf(w);
    if (!(density > 0)) return std::nullopt;
    return Sample{w, radiance(w), density};
}

uint64_t EnvironmentMap::hash() const {
    Hasher hasher;
    hasher.add(std::string_view("environment map"));
    hasher.add(!m_image.pixels.empty());
    if (m_image.pixels.empty()) {
        hasher.add(m_radiance);
        return hasher.value();
    }
    hasher.add(m_image.width);
    hasher.add(m_image.height);
    for (const Rgb& p : m_image.pixels) hasher.add(p);
    hasher.add(m_strength);
    hasher.add(m_rotation_degrees);
    return hasher.value();
}

}  // namespace steadylight
