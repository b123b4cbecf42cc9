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
//   quarter of each radius: a table top's coarse discs do not read the floor under it); the finest estimate is the coarsest plus each level's detail
//   (its estimate minus the next coarser one's), a Laplacian pyramid of the correction;
// - each detail is kept only where it stands out of its own noise: its standard error is known
//   from the photons it sums (Poisson: the square root of the sum of squared weighted powers).
//   Within noise_sigmas standard errors of zero it is dropped, beyond signal_sigmas kept whole,
//   linearly in between (firm shrinkage, Gao & Bruce 1997): scale-free, continuous (a detail
//   fades in rather than pops), and unbiased for clear signals. Far from the objects every
//   detail is noise, the correction is exactly 0, and the record does not change at all;
// - each level's kernel is divided by the share of its disc on the record's surface
//   (surface_coverage.h), without which coarse discs reaching past a wall's edge read too few
//   photons (the corridor's frames came out 0.4% bright).
#pragma once

#include <memory>
#include <mutex>
#include <vector>

#include "steadylight/irradiance/irradiance_cache.h"
#include "steadylight/passes/localized_settings.h"
#include "steadylight/photons/photon_map.h"
#include "steadylight/shading/frame_context.h"

namespace steadylight {

/// The share of each static record's discs (one per level) on its surface, from the static
/// geometry alone, computed once on first use (thread-safe) and kept for every frame of the
/// segment: a function of the segment, whichever frame asks first.
class CorrectionCoverage {
public:
    /// Record i's share at level l is at [i * settings.levels + l].
    const std::vector<float>& shares(const FrameContext& context, const IrradianceCache& cache,
                                     const CorrectionSettings& settings) const;

private:
    mutable std::once_flag m_once;
    mutable std::vector<float> m_shares;
    mutable int m_levels = 0;
};

/// The irradiance change at p (normal n) that the dynamic photons say is there, beyond their
/// noise (above). `shares` are the point's disc shares per level (nullptr: whole discs).
Rgb correction_at(const PhotonMap& dynamic, Vec3 p, Vec3 n, const CorrectionSettings& settings, const float* shares);

/// The static records with correction_at added at each (negative results clamped to 0). `shares`
/// from CorrectionCoverage (may be empty when `dynamic` is). `changed`, when given, gets a flag
/// per record: whether its irradiance changed.
IrradianceCache corrected_cache(const IrradianceCache& static_cache, const PhotonMap& dynamic,
                                const CorrectionSettings& settings, const std::vector<float>& shares,
                                std::vector<uint8_t>* changed = nullptr);

}  // namespace steadylight
