// Two-pass photon mapping with final gathering and an irradiance cache (Jensen 2001; the paper's
// reference method, DESIGN.md §2.4), every frame from scratch:
//   photon tracing (global and caustic maps) -> irradiance at photons, computed as needed (Christensen
//   1999) -> irradiance cache over the image by final gathering -> per pixel
//   L_r = L_d + L_i + L_c + L_s (shading_pass.h).
// The localized method (paper §3, localized.h) reuses these pieces with a static cache.
#pragma once

#include "steadylight/base/image.h"
#include "steadylight/integrators/frame_context.h"
#include "steadylight/integrators/frame_stats.h"
#include "steadylight/integrators/shading_pass.h"
#include "steadylight/irradiance/cache_builder.h"
#include "steadylight/photons/photon_tracer.h"

namespace steadylight {

struct PhotonMappingSettings {
    PhotonSettings photons;
    DensitySettings irradiance_estimate{.k = 50, .max_radius = 0.5f};  // at the precomputed photons
    int irradiance_stride = 4;        // precompute irradiance at every n-th global photon
    GatherSettings gather;
    CacheSettings cache;
    ShadingSettings shading;
};

/// The frame and its parts (AOVs). beauty = direct + indirect + caustic + specular.
struct PhotonFrame {
    Image beauty, direct, indirect, caustic, specular;
    Image records;  // 1 where an irradiance record projects, 0 elsewhere (paper Fig. 3)
    FrameStats stats;
};

PhotonFrame render_photon_mapped(const FrameContext& context, const PhotonMappingSettings& settings);

/// The first pass of every photon-mapping method: a frame's photon maps, and the irradiance
/// precomputed (lazily) at a share of its global photons. Construction traces the photons and
/// records the counts and the time in `stats`. Never copied or moved: `irradiance` refers to
/// `maps.global`.
struct FramePhotons {
    FramePhotons(const FrameContext& context, const PhotonMappingSettings& settings, FrameStats& stats);
    FramePhotons(const FramePhotons&) = delete;
    FramePhotons& operator=(const FramePhotons&) = delete;

    TracedPhotons maps;
    IrradiancePhotons irradiance;
};

/// Moves the shading pass's common layers into a frame that has members of the same names.
template <class FrameImages>
void take_common_layers(ShadedFrame& shaded, FrameImages& out) {
    out.beauty = std::move(shaded.beauty);
    out.direct = std::move(shaded.direct);
    out.indirect = std::move(shaded.indirect);
    out.caustic = std::move(shaded.caustic);
    out.specular = std::move(shaded.specular);
}

/// Indirect irradiance from `cache`, or, where no record reaches even twice as far, from a gather
/// at the point (not kept, so the cache never depends on shading order). Counts the fallbacks.
Rgb cached_irradiance(const IrradianceCache& cache, const SurfacePoint& sp, Vec3 n,
                      const std::function<GatherResult(const SurfacePoint&, Vec3)>& gather, std::atomic<long>& fallbacks,
                      std::atomic<long>& gather_rays);

}  // namespace steadylight
