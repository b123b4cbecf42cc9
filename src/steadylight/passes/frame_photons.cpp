// Tracing a frame's photons as a phase of the frame (frame_photons.h).
#include "steadylight/passes/frame_photons.h"

#include "steadylight/photons/surface_coverage.h"

namespace steadylight {
namespace {

/// The photons traced whole, or composed from the static paths; counts the paths retraced.
/// With `static_irradiance`, `reuse` gets what the irradiance at photons may take from it.
TracedPhotons frame_maps(const FrameContext& context, const PhotonMappingSettings& settings, FrameStats& stats,
                         const StaticPhotonPaths* paths, bool compose, const IrradiancePhotons* static_irradiance,
                         ChangedValues changed, FramePhotons::CausticChanges& caustic_changes,
                         std::shared_ptr<const StaticIrradianceReuse>& reuse) {
    const auto reuse_of = [&](const PhotonMap& global, KeptStaticPhotons kept) {
        if (static_irradiance)
            reuse = make_static_irradiance_reuse(*static_irradiance, paths->global.photons, global, std::move(kept),
                                                 changed, context.tracer.dynamic_bounds());
    };
    if (!paths || !compose) {
        TracedPhotons traced = trace_photons(context, settings.photons);
        if (paths) reuse_of(traced.global, kept_static_photons_by_bits(traced.global, paths->global.photons));
        return traced;
    }
    ComposedPhotons composed = compose_photons(context, *paths);
    stats.retraced_photon_paths = composed.retraced_paths + (composed.caustic_traced ? paths->caustic.count : 0);
    caustic_changes = {composed.caustic_traced, std::move(composed.changed_caustic_points)};
    reuse_of(composed.maps.global, std::move(composed.global_kept));
    return std::move(composed.maps);
}

/// The photon pass as a phase of the frame: traced, timed and counted in `stats`.
TracedPhotons trace_counted_photons(const FrameContext& context, const PhotonMappingSettings& settings,
                                    FrameStats& stats, const StaticPhotonPaths* paths, bool compose,
                                    const IrradiancePhotons* static_irradiance, ChangedValues changed,
                                    FramePhotons::CausticChanges& caustic_changes,
                                    std::shared_ptr<const StaticIrradianceReuse>& reuse) {
    TracedPhotons maps = timed_phase("photons", stats.photon_tracing_s, [&] {
        return frame_maps(context, settings, stats, paths, compose, static_irradiance, changed, caustic_changes, reuse);
    });
    stats.global_photons_emitted = maps.global.emitted();
    stats.global_photons_stored = long(maps.global.size());
    stats.caustic_photons_emitted = maps.caustic.emitted();
    stats.caustic_photons_stored = long(maps.caustic.size());
    stats.dynamic_photons_stored = long(maps.dynamic.size());
    if (!paths || !compose) stats.retraced_photon_paths = maps.global.emitted() + maps.caustic.emitted();  // every one
    return maps;
}

}  // namespace

FramePhotons::FramePhotons(const FrameContext& context, const PhotonMappingSettings& settings, FrameStats& stats,
                           const StaticPhotonPaths* paths, const IrradiancePhotons* static_irradiance,
                           ChangedValues changed, bool compose)
    : maps(trace_counted_photons(context, settings, stats, paths, compose, static_irradiance, changed, caustic_changes,
                                 static_reuse)),
      irradiance(maps.global, settings.irradiance_stride, settings.irradiance_estimate,
                 surface_coverage(context, Visibility::everything), static_reuse) {}

}  // namespace steadylight
