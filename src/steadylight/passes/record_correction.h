// L_t (paper §3.3): the static records corrected by the dynamic photon map, which holds what the
// moving objects changed (negative photons for path tails they removed, positive ones for the
// tails they added).
//
// The paper adds a 300-nearest-photon estimate of the dynamic map to each record. Far from the
// moving objects the few signed photons there are the tails of paths that met the object, and
// they land somewhere else in every frame: the estimate jumped from frame to frame while the
// true change there is tiny and smooth (BALL's L_t pixels changed by about 0.1% a frame where
// the light does not change). Here instead (docs/localized.md "A steady correction"):
// - a kernel estimate (Epanechnikov, smooth at its rim) at fixed radii r, 2r, 4r, ... per record,
//   one look-up at the largest, over the photons near the record's tangent plane (within a
//   quarter of each radius: a table top's coarse discs do not read the floor under it); the finest estimate is the
//   coarsest plus each level's detail (its estimate minus the next coarser one's), a Laplacian pyramid of the
//   correction;
// - each detail is kept only where it stands out of its own noise: its standard error is known
//   from the photons it sums (Poisson: the square root of the sum of squared weighted powers).
//   Within noise_sigmas standard errors of zero it is dropped, beyond signal_sigmas kept whole,
//   linearly in between (firm shrinkage, Gao & Bruce 1997): scale-free, continuous (a detail
//   fades in rather than pops), and unbiased for clear signals. Far from the objects every
//   detail is noise, the correction is exactly 0, and the record does not change at all;
// - each level's kernel is divided by the share of its weight on the record's surface, probed
//   once per segment (surface_coverage.h), without which coarse discs reaching past a wall's
//   edge read too few photons (the corridor's frames came out 0.4% bright). The probes see the
//   surface as the photons are chosen: any surface within the slab counts, seen from the slab's
//   top, so that a step lower than the slab hides nothing beyond it. Probed from just above the
//   surface, a record on a wall between stripes 2 cm proud of it found its disc stopped at the
//   stripes' sides, yet read the photons on the stripes beyond, divided by that small share: up
//   to 16 times (blender_glass's localized frames 1.8% dark, the stripes' change twice the true
//   one). The share weighs the probes by the kernel (the inner ring, the half of the disc's area
//   nearer the centre, holds 3/4 of the Epanechnikov weight): by area, a disc half a radius from
//   an edge read 9% too much. Levels whose disc has less than a quarter of the kernel's weight
//   on the surface are no estimate of its change (a 2 m disc on a 0.3 m ball: the few photons on
//   its top divided by a share of a few per cent made blotches): an estimate uses its levels up
//   to the first such one, and one whose finest disc is such gives no change (a small object
//   near the moving one takes L_y, by the influence there);
// - the two coarsest levels read the photons summed by cells (CorrectionPhotons), the finer ones
//   each photon: the coarse discs hold 15/16 of the photons a record reads. The kernel is a
//   quadratic in a photon's position, so a cell wholly inside a disc sums exactly from its
//   moments; a cell across the rim counts as its centroid. A record's own search then reaches a
//   quarter as far;
// - it is estimated at points, records a quarter of the finest radius apart, and taken from there
//   by the records between (CorrectionPoints): at production sizes the records stand a few
//   centimetres apart, and the change is smooth over the finest radius.
// docs/localized.md ("A steady correction") has what each of these changed.
#pragma once

#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include "steadylight/irradiance/irradiance_cache.h"
#include "steadylight/passes/localized_settings.h"
#include "steadylight/photons/photon_map.h"
#include "steadylight/photons/point_index.h"
#include "steadylight/shading/frame_context.h"

namespace steadylight {

/// Where L_t is estimated, and how each static record takes it: the correction is smooth over its
/// finest radius, while at production sizes the records are a few centimetres apart (25,800 on
/// BALL at 1280x960), so it is estimated at *points*, records at least `point_spacing` finest
/// radii apart (chosen in the records' order: a record is one unless a point already chosen lies
/// within that spacing on its surface), with their discs' probes (which cells of each level's disc
/// lie on the surface), and every other record takes the points within twice the spacing on its
/// surface, weighted by an Epanechnikov kernel (the one that blocked it weighs at least 3/4). A
/// point takes its own correction. Found from the static geometry and records alone, once, by
/// the first frame that asks (thread-safe), and kept for the frames of the segment.
class CorrectionPoints {
public:
    struct Taken {
        uint32_t point;
        float weight;  // a record's weights sum to 1
    };

    /// Chooses them for `cache`'s records, once (later calls must be for the same cache and settings).
    void make(const FrameContext& context, const IrradianceCache& cache, const CorrectionSettings& settings) const;

    size_t size() const { return m_records.size(); }
    /// How many records they were made for.
    size_t record_count() const { return m_first_taken.empty() ? 0 : m_first_taken.size() - 1; }
    /// The record point j is, and its discs' probes, one per level.
    uint32_t record(size_t point) const { return m_records[point]; }
    const DiscProbes* probes(size_t point) const { return &m_probes[point * size_t(m_levels)]; }
    /// The points record i takes its correction from.
    std::span<const Taken> taken(size_t record) const {
        return {m_taken.data() + m_first_taken[record], m_taken.data() + m_first_taken[record + 1]};
    }

private:
    mutable std::once_flag m_once;
    mutable int m_levels = 0;
    mutable std::vector<uint32_t> m_records;      // per point, ascending
    mutable std::vector<DiscProbes> m_probes;     // point j's at level l at [j * levels + l]
    mutable std::vector<uint32_t> m_first_taken;  // per record, and one past the last
    mutable std::vector<Taken> m_taken;
};

/// The radius of level `level`'s disc: settings.radius at the finest, doubling per level.
float level_radius(const CorrectionSettings& settings, int level);

/// The finest level that reads the photons summed by cells (CorrectionPhotons): the two coarsest,
/// never the finest.
int first_summed_level(const CorrectionSettings& settings);

/// The share of the correction kernel's weight in the cells `probes` found on the surface.
float kernel_share(const DiscProbes& probes);

/// The dynamic photons as the correction reads them: the map for the finer levels, and for the
/// coarse levels (first_summed_level on) the photons summed by cells, and by the direction of
/// their normals, so that a floor's and a wall's photons in one corner cell stay apart.
class CorrectionPhotons {
public:
    /// The photons of one cell whose normals point alike: their centroid c and mean normal, their
    /// summed power, power times offset x_j - c (per axis) and power times squared offset (the
    /// kernel's sum over a cluster wholly inside a disc is exact from these), the summed squared
    /// luminance (for the level's standard error), and the farthest photon's distance from c.
    struct Cluster {
        Vec3 p, n;
        Rgb power, power_offset[3], power_offset2;
        float luminance2 = 0, extent = 0;
    };

    /// Cells of `cell` scene units (default: a quarter of the first summed level's radius); 0
    /// sums nothing: every level reads every photon one by one.
    CorrectionPhotons(const PhotonMap& dynamic, const CorrectionSettings& settings, float cell = -1);

    const PhotonMap& map() const { return m_map; }
    /// Whether the coarse levels read the clusters (the settings have at least two levels).
    bool summed_by_cells() const { return m_summed_by_cells; }
    const std::vector<Cluster>& clusters() const { return m_clusters; }
    /// Every cluster whose centroid lies within `radius` of p.
    void clusters_within(Vec3 p, float radius, std::vector<Neighbour>& out) const;

private:
    const PhotonMap& m_map;
    bool m_summed_by_cells = false;
    std::vector<Cluster> m_clusters;
    PointIndex m_index;  // over the clusters' centroids
};

/// The irradiance change at p (normal n) that the dynamic photons say is there, beyond their
/// noise (above). `probes` are the point's discs per level (nullptr: whole discs).
Rgb correction_at(const CorrectionPhotons& dynamic, Vec3 p, Vec3 n, const CorrectionSettings& settings,
                  const DiscProbes* probes);

/// L_t's cache, the corrected cache: the static records with correction_at added, estimated at
/// `points` (made for this cache and settings; may be null when `dynamic` is empty) and taken
/// from there by every record (negative results clamped to 0). `changed`, when given, gets a flag
/// per record: whether its irradiance changed.
IrradianceCache correct_static_cache(const IrradianceCache& static_cache, const PhotonMap& dynamic,
                                     const CorrectionSettings& settings, const CorrectionPoints* points,
                                     std::vector<uint8_t>* changed = nullptr);

}  // namespace steadylight
