// Tracing a frame's photons as a phase of the frame (frame_photons.h).
#include "steadylight/passes/frame_photons.h"

#include "steadylight/photons/surface_coverage.h"

namespace steadylight {
namespace {

/// The photon pass as a phase of the frame: traced, timed and counted in `stats`.
TracedPhotons trace_counted_photons(const FrameContext& context, const PhotonMappingSettings& settings, FrameStats& stats) {
    TracedPhotons maps = timed_phase("photons", stats.photon_tracing_s, [&] { return trace_photons(context, settings.photons); });
    stats.global_photons_emitted = maps.global.emitted();
    stats.global_photons_stored = long(maps.global.size());
    stats.caustic_photons_emitted = maps.caustic.emitted();
    stats.caustic_photons_stored = long(maps.caustic.size());
    stats.dynamic_photons_stored = long(maps.dynamic.size());
    return maps;
}

}  // namespace

FramePhotons::FramePhotons(const FrameContext& context, const PhotonMappingSettings& settings, FrameStats& stats)
    : maps(trace_counted_photons(context, settings, stats)),
      irradiance(maps.global, settings.irradiance_stride, settings.irradiance_estimate,
                 surface_coverage(context, Visibility::everything)) {}

}  // namespace steadylight
