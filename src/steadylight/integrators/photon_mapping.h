// Two-pass photon mapping with final gathering and an irradiance cache (Jensen 2001; the paper's
// reference method, DESIGN.md §2.4), every frame from scratch:
//   photon tracing (global and caustic maps) -> irradiance precomputed at photons (Christensen
//   1999) -> irradiance cache over the image by final gathering -> per pixel
//   L_r = L_d + L_i + L_c + L_s (direct by shadow rays, indirect from the cache, caustics from
//   the caustic map, specular and glossy by recursive ray tracing).
// The localized method (paper §3) reuses these pieces with a static cache.
#pragma once

#include "steadylight/base/image.h"
#include "steadylight/integrators/frame_context.h"
#include "steadylight/integrators/frame_stats.h"
#include "steadylight/irradiance/cache_builder.h"
#include "steadylight/photons/photon_tracer.h"

namespace steadylight {

struct PhotonMappingSettings {
    PhotonSettings photons;
    DensitySettings irradiance_estimate{.k = 50, .max_radius = 0.5f};  // at the precomputed photons
    int irradiance_stride = 4;        // precompute irradiance at every n-th global photon
    DensitySettings caustic_estimate{.k = 50, .max_radius = 0.2f};
    GatherSettings gather;
    CacheSettings cache;
    int samples_per_pixel = 16;       // camera rays per pixel, stratified
    int direct_samples = 2;           // shadow rays per diffuse hit and camera ray, stratified over the pixel
    int max_specular_depth = 8;       // mirror, glass and glossy bounces followed from the camera
};

/// The frame and its parts (AOVs). beauty = direct + indirect + caustic + specular.
struct PhotonFrame {
    Image beauty, direct, indirect, caustic, specular;
    Image records;  // 1 where an irradiance record projects, 0 elsewhere (paper Fig. 3)
    FrameStats stats;
};

PhotonFrame render_photon_mapped(const FrameContext& context, const PhotonMappingSettings& settings);

}  // namespace steadylight
