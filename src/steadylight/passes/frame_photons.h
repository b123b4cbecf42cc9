// The first pass of every photon-mapping frame (Jensen 2001, ch. 5; paper §3.1): the frame's
// photons traced in the complete scene — the global, caustic and dynamic maps — and the
// irradiance precomputed (lazily) at a share of its global photons (Christensen 1999).
#pragma once

#include "steadylight/passes/frame_stats.h"
#include "steadylight/passes/photon_mapping_settings.h"
#include "steadylight/photons/photon_paths.h"

namespace steadylight {

/// A frame's photon maps and the irradiance at its photons. Construction traces the photons as
/// the phase "photons" and records the counts and the time in `stats`: all of them, or with
/// `paths` (the segment's static photon paths) and `compose` only those the dynamic objects
/// change, for the same maps (photon_paths.h). With paths and `static_irradiance` (over their
/// global map, probing the static scene) the irradiance at photons takes the static values where
/// nothing changed around them, for the same values (StaticIrradianceReuse), and where something
/// did does as `changed` says; traced whole, the frame's photons are told from the static ones
/// by their bits, for the same values again. Never copied or moved: `irradiance` refers to
/// `maps.global`, to `static_irradiance` and to `context`, which must outlive it.
struct FramePhotons {
    FramePhotons(const FrameContext& context, const PhotonMappingSettings& settings, FrameStats& stats,
                 const StaticPhotonPaths* paths = nullptr, const IrradiancePhotons* static_irradiance = nullptr,
                 ChangedValues changed = ChangedValues::searched, bool compose = true);
    FramePhotons(const FramePhotons&) = delete;
    FramePhotons& operator=(const FramePhotons&) = delete;

    /// How the caustic map differs from the static paths' one: everywhere (traced whole, or no
    /// static paths to tell), or where these photons were removed or added.
    struct CausticChanges {
        bool everywhere = true;
        std::vector<Vec3> points;
    } caustic_changes;
    /// What `irradiance` takes from the static values (null: nothing).
    std::shared_ptr<const StaticIrradianceReuse> static_reuse;
    TracedPhotons maps;
    IrradiancePhotons irradiance;
};

}  // namespace steadylight
