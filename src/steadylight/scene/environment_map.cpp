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

/// The side of the facing sampling's cells, in pixels.
constexpr int facing_cell_size = 16;

/// The fixed normals of the facing sampling: the cube's 6 faces, 12 edges and 8 corners, as
/// unit vectors.
const std::vector<Vec3>& facing_normals() {
    static const std::vector<Vec3> normals = [] {
        std::vector<Vec3> out;
        for (int z = -1; z <= 1; ++z)
            for (int y = -1; y <= 1; ++y)
                for (int x = -1; x <= 1; ++x)
                    if (x || y || z) out.push_back(normalize(Vec3{float(x), float(y), float(z)}));
        return out;
    }();
    return normals;
}

/// The index of the fixed normal nearest unit n.
int nearest_facing_normal(Vec3 n) {
    const std::vector<Vec3>& normals = facing_normals();
    int best = 0;
    for (int k = 1; k < int(normals.size()); ++k)
        if (dot(normals[size_t(k)], n) > dot(normals[size_t(best)], n)) best = k;
    return best;
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
    build_facing(weights);
}

int EnvironmentMap::cell_width(int cx) const {
    return std::min(facing_cell_size, m_image.width - cx * facing_cell_size);
}

void EnvironmentMap::build_facing(const std::vector<float>& weights) {
    const int width = m_image.width, height = m_image.height;
    m_cells_x = (width + facing_cell_size - 1) / facing_cell_size;
    m_cells_y = (height + facing_cell_size - 1) / facing_cell_size;
    const std::vector<Vec3>& normals = facing_normals();
    std::vector<std::vector<float>> facing(normals.size(), std::vector<float>(size_t(m_cells_x * m_cells_y), 0.0f));
    m_cell_pixels.reserve(size_t(m_cells_x * m_cells_y));
    for (int cy = 0; cy < m_cells_y; ++cy)
        for (int cx = 0; cx < m_cells_x; ++cx) {
            const int x0 = cx * facing_cell_size, y0 = cy * facing_cell_size;
            const int x1 = x0 + cell_width(cx), y1 = std::min(height, y0 + facing_cell_size);
            std::vector<float> pixels;
            pixels.reserve(size_t((x1 - x0) * (y1 - y0)));
            std::vector<double> sums(normals.size(), 0.0);
            for (int j = y0; j < y1; ++j)
                for (int i = x0; i < x1; ++i) {
                    const float weight = weights[size_t(j) * size_t(width) + size_t(i)];
                    pixels.push_back(weight);
                    const Vec3 w = direction_at({(float(i) + 0.5f) / float(width), (float(j) + 0.5f) / float(height)});
                    for (size_t k = 0; k < normals.size(); ++k)
                        sums[k] += double(weight) * std::max(0.0f, dot(w, normals[k]));
                }
            for (size_t k = 0; k < normals.size(); ++k) facing[k][size_t(cy * m_cells_x + cx)] = float(sums[k]);
            m_cell_pixels.emplace_back(std::move(pixels));
        }
    m_facing.reserve(normals.size());
    for (std::vector<float>& cells : facing) m_facing.emplace_back(std::move(cells));
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
    if (m_image.pixels.empty())
        w = sample_uniform_sphere(u);
    else
        w = direction_at(m_distribution.sample(u).uv);
    // From w itself, so that the sample agrees bit for bit with pdf(w) and radiance(w) (MIS
    // weights computed either way match).
    const float density = pdf(w);
    if (!(density > 0)) return std::nullopt;
    return Sample{w, radiance(w), density};
}

Vec3 EnvironmentMap::direction_at(Vec2 uv) const {
    const float theta = pi * uv.y, phi = 2 * pi * (uv.x - 0.5f);
    const float sin_theta = std::sin(theta);
    const float x = sin_theta * std::cos(phi), z = sin_theta * std::sin(phi);
    // Back from the image's frame: the inverse of image_point's rotation.
    return {x * m_cos_rotation - z * m_sin_rotation, std::cos(theta), x * m_sin_rotation + z * m_cos_rotation};
}

std::optional<EnvironmentMap::Sample> EnvironmentMap::sample_facing(Vec3 n, Vec2 u) const {
    if (m_black || m_image.pixels.empty()) return std::nullopt;
    // A cell by the fixed normal, a pixel in it, a point in the pixel: u.x's remainder at each
    // step chooses the next, u.y the point's row.
    const Distribution1D& cells = m_facing[size_t(nearest_facing_normal(n))];
    const Distribution1D::Sample cell = cells.sample(u.x);
    const float rest = std::clamp(cell.x * float(cells.size()) - float(cell.index), 0.0f, 0x1.fffffep-1f);
    const Distribution1D& pixels = m_cell_pixels[size_t(cell.index)];
    const Distribution1D::Sample pixel = pixels.sample(rest);
    const float across = std::clamp(pixel.x * float(pixels.size()) - float(pixel.index), 0.0f, 0x1.fffffep-1f);
    const int cx = cell.index % m_cells_x, cy = cell.index / m_cells_x, width = cell_width(cx);
    const int column = cx * facing_cell_size + pixel.index % width, row = cy * facing_cell_size + pixel.index / width;
    const Vec3 w =
        direction_at({(float(column) + across) / float(m_image.width), (float(row) + u.y) / float(m_image.height)});
    // From w itself, as sample() does.
    const float density = pdf_facing(n, w);
    if (!(density > 0)) return std::nullopt;
    return Sample{w, radiance(w), density};
}

float EnvironmentMap::pdf_facing(Vec3 n, Vec3 w) const {
    if (m_black || m_image.pixels.empty()) return 0;
    const ImagePoint point = image_point(w);
    if (!(point.sin_theta > 0)) return 0;
    const Distribution2D::Cell pixel = m_distribution.cell(point.uv);
    const int cx = pixel.column / facing_cell_size, cy = pixel.row / facing_cell_size;
    const int cell = cy * m_cells_x + cx;
    const int local = (pixel.row - cy * facing_cell_size) * cell_width(cx) + pixel.column - cx * facing_cell_size;
    const Distribution1D& cells = m_facing[size_t(nearest_facing_normal(n))];
    const Distribution1D& pixels = m_cell_pixels[size_t(cell)];
    const float density_uv = cells.cell_pdf(cell) / float(cells.size()) * pixels.cell_pdf(local) /
                             float(pixels.size()) * float(m_image.width) * float(m_image.height);
    return density_uv / (2 * pi * pi * point.sin_theta);
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
