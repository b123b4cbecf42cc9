#include "steadylight/photons/photon_map.h"

#include <cmath>

#include "steadylight/base/parallel.h"

namespace steadylight {
namespace {

std::vector<Vec3> positions_of(const std::vector<Photon>& photons) {
    std::vector<Vec3> positions;
    positions.reserve(photons.size());
    for (const Photon& photon : photons) positions.push_back(photon.p);
    return positions;
}

/// Photons arriving on the other side of a thin wall, or on a differently oriented surface
/// nearby, do not count (Jensen 2001 §7.2: "the normal ... filter").
bool same_side(const Photon& photon, Vec3 n) { return dot(photon.n, n) > 0.5f; }

/// The squared radius of an estimate that found `neighbours`.
float estimate_radius2(const std::vector<Neighbour>& neighbours, const DensitySettings& settings) {
    return int(neighbours.size()) < settings.k ? settings.max_radius * settings.max_radius
                                               : neighbours.back().distance2;
}

}  // namespace

PhotonMap::PhotonMap(std::vector<Photon> photons, long emitted)
    : m_photons(std::move(photons)), m_emitted(emitted), m_index(positions_of(m_photons)) {}

void PhotonMap::k_nearest(Vec3 p, int k, float max_radius, std::vector<Neighbour>& out) const {
    m_index.k_nearest(p, k, max_radius * max_radius, out);
}

Rgb PhotonMap::estimate_irradiance(Vec3 p, Vec3 n, const DensitySettings& settings) const {
    thread_local std::vector<Neighbour> neighbours;
    k_nearest(p, settings.k, settings.max_radius, neighbours);
    if (neighbours.empty()) return {};
    Rgb sum;
    for (const Neighbour& nb : neighbours)
        if (same_side(m_photons[nb.index], n)) sum += m_photons[nb.index].power;
    return sum / (pi * estimate_radius2(neighbours, settings));
}

Rgb PhotonMap::estimate_irradiance_cone(Vec3 p, Vec3 n, const DensitySettings& settings) const {
    thread_local std::vector<Neighbour> neighbours;
    k_nearest(p, settings.k, settings.max_radius, neighbours);
    if (neighbours.empty()) return {};
    const float r2 = estimate_radius2(neighbours, settings), r = std::sqrt(r2);
    Rgb sum;
    for (const Neighbour& nb : neighbours)
        if (same_side(m_photons[nb.index], n)) sum += m_photons[nb.index].power * (1 - std::sqrt(nb.distance2) / r);
    return sum / ((1 - 2.0f / 3.0f) * pi * r2);
}

IrradiancePhotons::IrradiancePhotons(const PhotonMap& global, int stride, const DensitySettings& settings) {
    const std::vector<Photon>& photons = global.photons();
    const size_t count = (photons.size() + size_t(stride) - 1) / size_t(stride);
    m_n.resize(count);
    m_E.resize(count);
    std::vector<Vec3> positions(count);
    parallel_for_chunks(long(count), 256, [&](long begin, long end) {
        for (long i = begin; i < end; ++i) {
            const Photon& photon = photons[size_t(i) * size_t(stride)];
            positions[size_t(i)] = photon.p;
            m_n[size_t(i)] = photon.n;
            m_E[size_t(i)] = global.estimate_irradiance(photon.p, photon.n, settings);
        }
    });
    m_index = PointIndex(std::move(positions));
}

std::optional<Rgb> IrradiancePhotons::lookup(Vec3 p, Vec3 n, float max_radius) const {
    // Most look-ups are answered by the single nearest photon; only near creases and thin walls
    // does its normal disagree, and then the next few are tried.
    thread_local std::vector<Neighbour> neighbours;
    for (const int k : {1, 8}) {
        m_index.k_nearest(p, k, max_radius * max_radius, neighbours);
        for (const Neighbour& nb : neighbours)
            if (dot(m_n[nb.index], n) > 0.5f) return m_E[nb.index];
        if (int(neighbours.size()) < k) break;  // nothing further within reach
    }
    return std::nullopt;
}

}  // namespace steadylight
