// L_t's correction of the static records (record_correction.h).
#include "steadylight/passes/record_correction.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "steadylight/base/check.h"
#include "steadylight/base/parallel.h"
#include "steadylight/base/rng.h"
#include "steadylight/photons/point_index.h"
#include "steadylight/photons/surface_coverage.h"

namespace steadylight {
namespace {

/// How much of a detail to keep: 0 within noise_sigmas standard errors of zero, all of it beyond
/// signal_sigmas, in between the share that makes the kept detail grow linearly from 0 to whole
/// (firm shrinkage).
float kept_share(float detail, float sigma, const CorrectionSettings& settings) {
    const float z = std::abs(detail) / sigma;  // no photons: 0 / 0, dropped below
    if (!(z > settings.noise_sigmas)) return 0;
    if (z >= settings.signal_sigmas) return 1;
    return settings.signal_sigmas * (z - settings.noise_sigmas) /
           ((settings.signal_sigmas - settings.noise_sigmas) * z);
}

/// A disc with less of the kernel's weight on the record's surface than this is no estimate of
/// that surface's change: on a small object (a 0.3 m ball) a 2 m disc holds the few photons of
/// the object's top, divided by a share of a few per cent, and the corrections came out blotchy.
constexpr float min_kernel_share = 0.25f;

/// How far off the tangent plane a level's photons may lie: a quarter of its radius (a table
/// top's coarse discs do not read the floor under it).
float slab_half_width(float radius) { return radius / 4; }

}  // namespace

float level_radius(const CorrectionSettings& settings, int level) { return settings.radius * float(1 << level); }

int first_summed_level(const CorrectionSettings& settings) { return std::max(1, settings.levels - 2); }

void CorrectionPoints::make(const FrameContext& context, const IrradianceCache& cache,
                            const CorrectionSettings& settings) const {
    std::call_once(m_once, [&] {
        const std::vector<IrradianceRecord>& records = cache.records();
        const float spacing = settings.point_spacing * settings.radius, reach = 2 * spacing;
        // On the record's surface: a point within the reach, its normal within 18 degrees of the
        // record's and no farther off the record's tangent plane than half the spacing (a table
        // top takes nothing from the floor under it, nor a wall from the floor at its foot).
        const auto on_surface_of = [&](const IrradianceRecord& record, const IrradianceRecord& point) {
            return dot(record.n, point.n) >= 0.95f && std::abs(dot(point.p - record.p, record.n)) <= spacing / 2;
        };
        std::vector<Vec3> positions(records.size());
        for (size_t i = 0; i < records.size(); ++i) positions[i] = records[i].p;
        const PointIndex all(positions);
        constexpr int32_t not_a_point = -1;
        std::vector<int32_t> point_of(records.size(), not_a_point);  // per record: which point it is
        std::vector<Neighbour> found;
        for (size_t i = 0; i < records.size(); ++i) {
            if (spacing > 0) all.within(records[i].p, spacing * spacing, found);
            const bool blocked = spacing > 0 && std::any_of(found.begin(), found.end(), [&](const Neighbour& near) {
                                     return near.index < i && point_of[near.index] != not_a_point &&
                                            on_surface_of(records[i], records[near.index]);
                                 });
            if (blocked) continue;
            point_of[i] = int32_t(m_records.size());
            m_records.push_back(uint32_t(i));
        }

        const int levels = settings.levels;
        m_levels = levels;
        const SurfaceCoverage coverage = surface_coverage(context, Visibility::static_only);
        m_probes.resize(m_records.size() * size_t(levels));
        parallel_for_chunks(long(m_records.size()), 16, [&](long begin, long end) {
            for (long j = begin; j < end; ++j) {
                const IrradianceRecord& record = records[m_records[size_t(j)]];
                for (int l = 0; l < levels; ++l) {
                    const float r = level_radius(settings, l);
                    // Probed as the photons are chosen: a surface within the slab counts, seen
                    // from its top (a step lower than the slab, such as stripes proud of a wall,
                    // does not hide the surface beyond).
                    const float slab = slab_half_width(r);
                    const uint64_t seed = uint64_t(m_records[size_t(j)]) * uint64_t(levels) + uint64_t(l);
                    m_probes[size_t(j) * size_t(levels) + size_t(l)] =
                        coverage.probes(record.p, record.n, r, slab, slab, seed);
                }
            }
        });

        std::vector<Vec3> point_positions(m_records.size());
        for (size_t j = 0; j < m_records.size(); ++j) point_positions[j] = records[m_records[j]].p;
        const PointIndex points(point_positions);
        std::vector<std::vector<Taken>> taken(records.size());
        parallel_for_chunks(long(records.size()), 256, [&](long begin, long end) {
            std::vector<Neighbour> near;
            for (long i = begin; i < end; ++i) {
                std::vector<Taken>& out = taken[size_t(i)];
                if (point_of[size_t(i)] != not_a_point) {
                    out.push_back({uint32_t(point_of[size_t(i)]), 1.0f});
                    continue;
                }
                points.within(records[size_t(i)].p, reach * reach, near);
                std::sort(near.begin(), near.end(), nearer_neighbour);
                float sum = 0;
                for (const Neighbour& point : near)
                    if (on_surface_of(records[size_t(i)], records[m_records[point.index]])) {
                        const float weight = 1 - point.distance2 / (reach * reach);
                        if (weight > 0) out.push_back({point.index, weight}), sum += weight;
                    }
                SL_CHECK(sum > 0);  // the point that kept it from being one is among them
                for (Taken& t : out) t.weight /= sum;
            }
        });
        m_first_taken.resize(records.size() + 1);
        for (size_t i = 0; i < records.size(); ++i) {
            m_first_taken[i] = uint32_t(m_taken.size());
            m_taken.insert(m_taken.end(), taken[i].begin(), taken[i].end());
        }
        m_first_taken[records.size()] = uint32_t(m_taken.size());
    });
    SL_CHECK_EQ(m_levels, settings.levels);
}

float kernel_share(const DiscProbes& probes) {
    // The kernel 1 - d^2/r^2 puts 3/4 of its weight inside d^2 = r^2/2 (the inner ring's cells)
    // and 1/4 outside; each ring has DiscProbes::sectors equal cells.
    static_assert(DiscProbes::rings == 2);
    constexpr uint16_t inner_ring = (1u << DiscProbes::sectors) - 1;
    const int inner = std::popcount(uint16_t(probes.reached & inner_ring));
    const int outer = std::popcount(uint16_t(probes.reached & ~inner_ring));
    return float(3 * inner + outer) / float(4 * DiscProbes::sectors);
}

CorrectionPhotons::CorrectionPhotons(const PhotonMap& dynamic, const CorrectionSettings& settings, float cell)
    : m_map(dynamic) {
    if (cell < 0) cell = level_radius(settings, first_summed_level(settings)) / 4;
    m_summed_by_cells = cell > 0 && settings.levels >= 2;
    if (!m_summed_by_cells) return;
    const std::vector<Photon>& photons = dynamic.photons();
    // A cell's photons by the direction of their normals in steps of an eighth: a flat surface's
    // photons share one, a curved one's split where the normal filter would tell them apart.
    struct Key {
        int64_t x, y, z;
        int32_t n[3];
        bool operator==(const Key&) const = default;
    };
    struct KeyHash {
        size_t operator()(const Key& k) const {
            const uint64_t normal = uint64_t(k.n[0] + 8) | uint64_t(k.n[1] + 8) << 8 | uint64_t(k.n[2] + 8) << 16;
            return size_t(hash_ids(uint64_t(k.x), uint64_t(k.y), uint64_t(k.z), normal));
        }
    };
    std::unordered_map<Key, uint32_t, KeyHash> cluster_of;
    std::vector<uint32_t> photon_cluster(photons.size());
    std::vector<Vec3> position_sums, normal_sums;
    std::vector<int> counts;
    for (size_t i = 0; i < photons.size(); ++i) {
        const Photon& photon = photons[i];
        const Key key{int64_t(std::floor(photon.p.x / cell)),
                      int64_t(std::floor(photon.p.y / cell)),
                      int64_t(std::floor(photon.p.z / cell)),
                      {int32_t(std::lround(photon.n.x * 8)), int32_t(std::lround(photon.n.y * 8)),
                       int32_t(std::lround(photon.n.z * 8))}};
        const uint32_t at = cluster_of.try_emplace(key, uint32_t(position_sums.size())).first->second;
        if (at == position_sums.size()) position_sums.emplace_back(), normal_sums.emplace_back(), counts.push_back(0);
        photon_cluster[i] = at;
        position_sums[at] += photon.p, normal_sums[at] += photon.n, ++counts[at];
    }
    m_clusters.resize(position_sums.size());
    std::vector<Vec3> centroids(m_clusters.size());
    for (size_t c = 0; c < m_clusters.size(); ++c) {
        m_clusters[c].p = centroids[c] = position_sums[c] / float(counts[c]);
        m_clusters[c].n = normalize(normal_sums[c]);
    }
    // The moments about the centroid, which make a quadratic kernel's sum exact.
    for (size_t i = 0; i < photons.size(); ++i) {
        const Photon& photon = photons[i];
        Cluster& cluster = m_clusters[photon_cluster[i]];
        const Vec3 offset = photon.p - cluster.p;
        const float y = luminance(photon.power);
        cluster.power += photon.power;
        cluster.power_offset[0] += photon.power * offset.x;
        cluster.power_offset[1] += photon.power * offset.y;
        cluster.power_offset[2] += photon.power * offset.z;
        cluster.power_offset2 += photon.power * length2(offset);
        cluster.luminance2 += y * y;
        cluster.extent = std::max(cluster.extent, length(offset));
    }
    m_index = PointIndex(centroids);
}

void CorrectionPhotons::clusters_within(Vec3 p, float radius, std::vector<Neighbour>& out) const {
    m_index.within(p, radius * radius, out);
}

Rgb correction_at(const CorrectionPhotons& dynamic, Vec3 p, Vec3 n, const CorrectionSettings& settings,
                  const DiscProbes* probes) {
    SL_CHECK(settings.levels >= 1 && settings.levels <= max_correction_levels);
    // The levels up to the first whose disc lies less than min_kernel_share on the surface.
    float share[max_correction_levels];
    int levels = 0;
    for (; levels < settings.levels; ++levels) {
        share[levels] = probes ? kernel_share(probes[levels]) : 1.0f;
        if (share[levels] < min_kernel_share) break;
    }
    if (levels == 0) return {};
    // Level l's kernel: (1 - d^2 / r_l^2) 2 / (pi r_l^2 share_l) inside r_l, share_l its weight
    // on the surface; it integrates to 1 over the part of the disc on the surface.
    float radius[max_correction_levels], inverse_r2[max_correction_levels], scale[max_correction_levels];
    for (int l = 0; l < levels; ++l) {
        radius[l] = level_radius(settings, l);
        inverse_r2[l] = 1 / (radius[l] * radius[l]);
        scale[l] = 2 * inverse_r2[l] / (pi * share[l]);
    }
    const auto kernel = [&](int l, float offset, float distance2) {
        const bool in_disc = offset <= slab_half_width(radius[l]);
        return in_disc ? std::max(0.0f, 1 - distance2 * inverse_r2[l]) * scale[l] : 0.0f;
    };
    Rgb detail[max_correction_levels];
    float variance[max_correction_levels] = {};
    // A record with every level reads the coarse levels (from first_summed on) from the cells,
    // and its photons one by one only within the finer discs. Its details are still each level's
    // estimate less the next coarser one's over every photon: the coarse levels' details and
    // variances come from the cells alone; the next finer level's detail takes the cells' estimate
    // off, and its variance, the squared weights (k_finer - k_summed)^2 of every photon, is
    // (k_finer - k_summed)^2 - k_summed^2 summed over the photons within the finer disc plus the
    // cells' k_summed^2.
    const int first_summed =
        dynamic.summed_by_cells() && levels == settings.levels ? first_summed_level(settings) : levels;
    thread_local std::vector<Neighbour> found;
    dynamic.map().within(p, radius[first_summed - 1], found);
    float summed_variance_offset = 0;
    for (const Neighbour& neighbour : found) {
        const Photon& photon = dynamic.map().photons()[neighbour.index];
        if (!same_side(photon, n)) continue;
        const float y = luminance(photon.power);
        const float offset = std::abs(dot(photon.p - p, n));
        // Finer discs lie inside coarser ones, slab and all: once a level's kernel is 0, so is
        // every finer one's, and their details gain exactly 0. Most photons lie in the coarsest
        // disc alone (three quarters of its area).
        float coarser = 0;  // the next coarser level's kernel; 0 past the coarsest read here
        for (int l = first_summed - 1; l >= 0; --l) {
            const float k = kernel(l, offset, neighbour.distance2);
            const float weight = k - coarser;
            detail[l] += photon.power * weight;
            if (l == first_summed - 1 && first_summed < levels) {
                const float summed = kernel(first_summed, offset, neighbour.distance2);
                summed_variance_offset += y * y * ((k - summed) * (k - summed) - summed * summed);
            } else {
                variance[l] += (y * weight) * (y * weight);
            }
            if (k == 0) break;
            coarser = k;
        }
    }
    if (first_summed < levels) {
        Rgb estimate[max_correction_levels + 1];  // per summed level, over every photon
        float summed_variance = 0;                // the cells' k_first_summed^2
        dynamic.clusters_within(p, radius[levels - 1], found);
        for (const Neighbour& neighbour : found) {
            const CorrectionPhotons::Cluster& cluster = dynamic.clusters()[neighbour.index];
            if (!same_side(cluster.n, n)) continue;
            const float offset = std::abs(dot(cluster.p - p, n));
            const float distance = std::sqrt(neighbour.distance2);
            const Vec3 to = cluster.p - p;
            float coarser = 0;
            for (int l = levels - 1; l >= first_summed; --l) {
                const float k = kernel(l, offset, neighbour.distance2);  // at the centroid
                if (distance + cluster.extent < radius[l] && offset + cluster.extent <= slab_half_width(radius[l])) {
                    // Wholly inside the disc and its slab: the sum of P_j (1 - |x_j - p|^2 / r^2)
                    // from the moments, |x_j - p|^2 = |x_j - c|^2 + 2 (x_j - c) . (c - p) + |c - p|^2.
                    const Rgb distance2_sum = cluster.power_offset2 +
                                              (cluster.power_offset[0] * to.x + cluster.power_offset[1] * to.y +
                                               cluster.power_offset[2] * to.z) *
                                                  2.0f +
                                              cluster.power * neighbour.distance2;
                    estimate[l] += (cluster.power - distance2_sum * inverse_r2[l]) * scale[l];
                } else {
                    estimate[l] += cluster.power * k;  // across the rim: as its centroid
                }
                variance[l] += cluster.luminance2 * (k - coarser) * (k - coarser);
                if (l == first_summed) summed_variance += cluster.luminance2 * k * k;
                if (k == 0) break;
                coarser = k;
            }
        }
        for (int l = first_summed; l < levels; ++l) detail[l] = estimate[l] - estimate[l + 1];
        detail[first_summed - 1] = detail[first_summed - 1] - estimate[first_summed];
        variance[first_summed - 1] = std::max(0.0f, summed_variance_offset + summed_variance);
    }
    Rgb sum;
    for (int l = 0; l < levels; ++l)
        sum += detail[l] * kept_share(luminance(detail[l]), std::sqrt(variance[l]), settings);
    return sum;
}

IrradianceCache correct_static_cache(const IrradianceCache& static_cache, const PhotonMap& dynamic,
                                     const CorrectionSettings& settings, const CorrectionPoints* points,
                                     std::vector<uint8_t>* changed) {
    std::vector<IrradianceRecord> records = static_cache.records();
    if (changed) changed->assign(records.size(), 0);
    if (dynamic.size() > 0) {
        SL_CHECK(points && points->record_count() == records.size());
        const CorrectionPhotons photons(dynamic, settings);
        std::vector<Rgb> corrections(points->size());
        parallel_for_chunks(long(points->size()), 64, [&](long begin, long end) {
            for (long j = begin; j < end; ++j) {
                const IrradianceRecord& r = records[points->record(size_t(j))];
                corrections[size_t(j)] = correction_at(photons, r.p, r.n, settings, points->probes(size_t(j)));
            }
        });
        parallel_for_chunks(long(records.size()), 256, [&](long begin, long end) {
            for (long i = begin; i < end; ++i) {
                Rgb delta;
                for (const CorrectionPoints::Taken& taken : points->taken(size_t(i)))
                    if (corrections[taken.point] != Rgb{}) delta += corrections[taken.point] * taken.weight;
                if (delta == Rgb{}) continue;  // the record as it is, bit for bit
                IrradianceRecord& r = records[size_t(i)];
                const Rgb E = {std::max(0.0f, r.E.r + delta.r), std::max(0.0f, r.E.g + delta.g),
                               std::max(0.0f, r.E.b + delta.b)};
                if (changed) (*changed)[size_t(i)] = E != r.E;
                r.E = E;
            }
        });
    }
    return static_cache.with_irradiance(std::move(records));
}

}  // namespace steadylight
