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

}  // namespace

DistantPhotonTargets::DistantPhotonTargets(const BoundingSphere& scene,
                                           const std::vector<std::pair<Vec3, Vec3>>& crossings)
    : m_scene(scene),
      m_radius(std::max(scene.radius, 1e-3f)),
      m_marks(size_t(direction_bins * direction_bins), std::vector<uint8_t>(size_t(cells * cells), 0)),
      m_marked(size_t(direction_bins * direction_bins)) {
    for (const auto& [d, p] : crossings) {
        const Vec2 xy = plane_coordinates(d, p);
        const float cell_size = 2 * m_radius / cells;
        const int i = int(std::floor((xy.x + m_radius) / cell_size)),
                  j = int(std::floor((xy.y + m_radius) / cell_size));
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

int DistantPhotonTargets::bin_of(Vec3 d) const {
    const float sum = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
    float x = d.x / sum, y = d.y / sum;
    if (d.z < 0) {
        const float folded_x = (1 - std::abs(y)) * std::copysign(1.0f, x);
        y = (1 - std::abs(x)) * std::copysign(1.0f, y);
        x = folded_x;
    }
    const int i = std::clamp(int((x + 1) * 0.5f * direction_bins), 0, direction_bins - 1);
    const int j = std::clamp(int((y + 1) * 0.5f * direction_bins), 0, direction_bins - 1);
    return j * direction_bins + i;
}

Vec2 DistantPhotonTargets::plane_coordinates(Vec3 d, Vec3 p) const {
    const OrthonormalBasis basis = OrthonormalBasis::from_normal(d);
    return {dot(p - m_scene.center, basis.s), dot(p - m_scene.center, basis.t)};
}

int DistantPhotonTargets::cell_of(Vec2 xy) const {
    const float cell_size = 2 * m_radius / cells;
    const int i = int(std::floor((xy.x + m_radius) / cell_size)), j = int(std::floor((xy.y + m_radius) / cell_size));
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
