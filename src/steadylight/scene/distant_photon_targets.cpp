#include "steadylight/scene/distant_photon_targets.h"

#include <algorithm>
#include <cmath>

#include "steadylight/base/hash.h"
#include "steadylight/base/sampling.h"

namespace steadylight {
namespace {

constexpr int direction_bins = 32;  // per side of the octahedral map of travel directions
constexpr int cells = 32;           // per side of the disc's grid
constexpr float aimed_share = 0.75f;

/// Where unit `d` falls on the octahedral map, a square [-1, 1]^2: the octahedron |x|+|y|+|z| = 1
/// seen from above, its lower half folded out over the corners.
Vec2 octahedral_square(Vec3 d) {
    const float sum = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
    const float x = d.x / sum, y = d.y / sum;
    if (d.z >= 0) return {x, y};
    return {(1 - std::abs(y)) * std::copysign(1.0f, x), (1 - std::abs(x)) * std::copysign(1.0f, y)};
}

/// The unit direction at a point of the square: octahedral_square's inverse.
Vec3 octahedral_direction(Vec2 q) {
    const float z = 1 - std::abs(q.x) - std::abs(q.y);
    Vec3 p{q.x, q.y, z};
    if (z < 0) {
        p.x = (1 - std::abs(q.y)) * std::copysign(1.0f, q.x);
        p.y = (1 - std::abs(q.x)) * std::copysign(1.0f, q.y);
    }
    return normalize(p);
}

/// Solid angle per area of the square at unit `d`: the octahedron's point d / |d|_1, at distance
/// 1 / |d|_1 with its face's normal at cos 1 / (√3 |p|) to it, seen through a face tilted by
/// 1 / √3 to the square, gives dω = |d|_1^3 dA.
float solid_angle_per_area(Vec3 d) {
    const float sum = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
    return sum * sum * sum;
}

int bin_of(Vec3 d) {
    const Vec2 q = octahedral_square(d);
    const int i = std::clamp(int((q.x + 1) * 0.5f * direction_bins), 0, direction_bins - 1);
    const int j = std::clamp(int((q.y + 1) * 0.5f * direction_bins), 0, direction_bins - 1);
    return j * direction_bins + i;
}

/// The area of a bin's square on the map (the map is 2 x 2).
constexpr float bin_area = 4.0f / float(direction_bins * direction_bins);

/// The point of the map at fractions f (each in [0, 1)) across and up bin's square.
Vec2 bin_point(int bin, Vec2 f) {
    const float size = 2.0f / direction_bins;
    return {-1 + (float(bin % direction_bins) + f.x) * size, -1 + (float(bin / direction_bins) + f.y) * size};
}

}  // namespace

AimedDirections::Sample AimedDirections::sample(Vec2 u) const {
    const Distribution1D::Sample bin = m_bins.sample(u.x);
    const Vec3 d = octahedral_direction(bin_point(bin.index, {u.y, bin.x * float(m_bins.size()) - float(bin.index)}));
    return {d, pdf(d)};
}

float AimedDirections::pdf(Vec3 d) const {
    const float bin_probability = m_bins.cell_pdf(bin_of(d)) / float(m_bins.size());
    return bin_probability / (bin_area * solid_angle_per_area(d));
}

DistantPhotonTargets::DistantPhotonTargets(const BoundingSphere& scene,
                                           const std::vector<std::pair<Vec3, Vec3>>& crossings)
    : m_scene(scene),
      m_radius(std::max(scene.radius, 1e-3f)),
      m_marks(size_t(direction_bins * direction_bins), std::vector<uint8_t>(size_t(cells * cells), 0)),
      m_marked(size_t(direction_bins * direction_bins)) {
    for (const auto& [d, p] : crossings) {
        const auto [i, j] = grid_cell(plane_coordinates(d, p));
        std::vector<uint8_t>& marks = m_marks[size_t(bin_of(d))];
        // The neighbours too: a direction elsewhere in the bin crosses the same opening a little
        // aside.
        for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di)
                if (i + di >= 0 && i + di < cells && j + dj >= 0 && j + dj < cells)
                    marks[size_t((j + dj) * cells + i + di)] = 1;
    }
    for (size_t bin = 0; bin < m_marks.size(); ++bin)
        for (int cell = 0; cell < cells * cells; ++cell)
            if (m_marks[bin][size_t(cell)]) m_marked[bin].push_back(cell);
}

Vec2 DistantPhotonTargets::plane_coordinates(Vec3 d, Vec3 p) const {
    const OrthonormalBasis basis = OrthonormalBasis::from_normal(d);
    return {dot(p - m_scene.center, basis.s), dot(p - m_scene.center, basis.t)};
}

std::pair<int, int> DistantPhotonTargets::grid_cell(Vec2 xy) const {
    const float cell_size = 2 * m_radius / cells;
    return {int(std::floor((xy.x + m_radius) / cell_size)), int(std::floor((xy.y + m_radius) / cell_size))};
}

int DistantPhotonTargets::cell_of(Vec2 xy) const {
    const auto [i, j] = grid_cell(xy);
    return i >= 0 && i < cells && j >= 0 && j < cells ? j * cells + i : -1;
}

DistantPhotonTargets::Start DistantPhotonTargets::sample_start(Vec3 d, Vec2 u) const {
    const int bin = bin_of(d);
    const std::vector<int>& marked = m_marked[size_t(bin)];
    const float aimed = marked.empty() ? 0 : aimed_share;
    const float cell_size = 2 * m_radius / cells;
    Vec2 xy;
    if (u.x < aimed) {
        const float scaled = u.x / aimed * float(marked.size());
        const size_t k = std::min(size_t(scaled), marked.size() - 1);
        const int cell = marked[k];
        const float rest = std::min(scaled - float(k), 0x1.fffffep-1f);
        xy = {-m_radius + (float(cell % cells) + rest) * cell_size,
              -m_radius + (float(cell / cells) + u.y) * cell_size};
    } else {
        const float v = std::min((u.x - aimed) / (1 - aimed), 0x1.fffffep-1f);
        const float r = m_radius * std::sqrt(v), phi = 2 * pi * u.y;
        xy = {r * std::cos(phi), r * std::sin(phi)};
    }
    const int cell = cell_of(xy);
    const bool in_disc = xy.x * xy.x + xy.y * xy.y <= m_radius * m_radius;
    float pdf = in_disc ? (1 - aimed) / (pi * m_radius * m_radius) : 0.0f;
    if (cell >= 0 && m_marks[size_t(bin)][size_t(cell)]) pdf += aimed / (float(marked.size()) * cell_size * cell_size);
    const OrthonormalBasis basis = OrthonormalBasis::from_normal(d);
    return {m_scene.center - d * (m_radius * 1.01f) + basis.s * xy.x + basis.t * xy.y, pdf};
}

std::optional<AimedDirections> DistantPhotonTargets::aimed_directions(
    const std::function<float(Vec3)>& luminance) const {
    // A bin's light: its luminance integrated over the bin's solid angle, from a grid of
    // directions in it (an image's small bright sun may fall between them: the light's own
    // sampling keeps it).
    constexpr int grid = 6;
    std::vector<float> weights(m_marked.size(), 0.0f);
    bool any = false;
    for (size_t bin = 0; bin < m_marked.size(); ++bin) {
        if (m_marked[bin].empty()) continue;
        double light = 0;
        for (int b = 0; b < grid; ++b)
            for (int a = 0; a < grid; ++a) {
                const Vec3 d =
                    octahedral_direction(bin_point(int(bin), {(float(a) + 0.5f) / grid, (float(b) + 0.5f) / grid}));
                light += double(luminance(d)) * solid_angle_per_area(d);
            }
        weights[bin] = float(light / (grid * grid) * bin_area * double(m_marked[bin].size()));
        any = any || weights[bin] > 0;
    }
    if (!any) return std::nullopt;
    return AimedDirections(Distribution1D(std::move(weights)));
}

size_t DistantPhotonTargets::marked_cells() const {
    size_t n = 0;
    for (const std::vector<int>& marked : m_marked) n += marked.size();
    return n;
}

uint64_t DistantPhotonTargets::hash() const {
    Hasher h;
    for (const std::vector<int>& marked : m_marked) {
        h.add(int(marked.size()));
        if (!marked.empty()) h.add(marked.data(), marked.size() * sizeof(int));
    }
    return h.value();
}

}  // namespace steadylight
