// The localized method (Tawara, Myszkowski & Seidel 2002, §3; DESIGN.md §2), the default:
//   segment pass, once: static photons (dynamic objects removed) -> static irradiance cache over
//     every camera view of the segment, by final gathering against the static photons;
//   frame pass, each frame: photons in the complete scene (global, caustic and dynamic maps) ->
//     influence I of the dynamic objects per pixel -> L_y, a dynamic cache built only where
//     I > tau_l and on dynamic objects -> L_t, the static records corrected by the dynamic map ->
//     L_i = smoothstep blend of L_y and L_t -> L_d + L_i + L_c + L_s (shading_pass.h).
// "frozen" is the cheap production practice it is compared with: the static cache as it is for
// static points, and L_y on dynamic objects only.
#pragma once

#include <string>

#include "steadylight/integrators/photon_mapping.h"

namespace steadylight {

struct LocalizedSettings {
    PhotonMappingSettings base;   // photons (static and per frame alike), gathering, cache, shading
    int influence_photons = 300;  // N nearest dynamic photons in the influence estimate (paper: 300)
    /// The dynamic map's estimate that corrects the static records (L_t). Many photons: a noisy
    /// correction changes from frame to frame and flickers (k = 50 flickered more than the
    /// photon method on TABLE; 300 flickers 25% less than it).
    DensitySettings correction_estimate{.k = 300, .max_radius = 0.5f};
    int influence_step = 4;       // influence estimated at every n-th pixel centre in x and y (it is smooth)
    /// Thresholds on the influence relative to the static indirect irradiance there: below
    /// tau_lower L_t alone, above tau_upper L_y alone, smoothstep between (paper §3.3). Why these
    /// values: L_t's correction is a density estimate of the dynamic photons, whose noise is about
    /// I / sqrt(k) for k photons (k = 300): at I = 0.3 that is ~2% of the static indirect
    /// irradiance, at I = 1 ~6%, past which L_t cannot be trusted (docs/localized.md).
    float tau_lower = 0.3f;
    float tau_upper = 1.0f;
    bool frozen = false;          // the "frozen cache" baseline instead of the localized method
};

/// What the segment pass leaves for every frame: the static irradiance cache.
struct StaticSolution {
    IrradianceCache cache;
    long records = 0;
    double seconds = 0;
    bool loaded = false;        // read from the cache file instead of computed
    std::string file_note;      // why the file was not used, when it was not
};

/// A hash of everything the static cache of frames [first, last] depends on: the static objects
/// and their materials, the lights, every camera view, and the settings that shape the cache.
uint64_t static_inputs_hash(const Scene& scene, int first, int last, const LocalizedSettings& settings);

/// The segment pass over frames [first, last] of the scene: static photons and the static cache
/// over every distinct camera view. Moves `tracer` through the frames. With a `cache_file`, a
/// file made from the same inputs is loaded instead, and a computed cache is saved there.
StaticSolution run_segment_pass(const Scene& scene, RayTracer& tracer, int first, int last,
                                const LocalizedSettings& settings, const std::string& cache_file = "");

struct LocalizedFrame {
    Image beauty, direct, indirect, caustic, specular;
    Image indirect_static;  // L_i from the static cache alone (paper Fig. 1d)
    Image L_y, L_t;         // the two estimates, as radiance (Fig. 1e, 1f)
    Image influence;        // I relative to the static indirect irradiance (Fig. 4d, 5)
    Image static_records, dynamic_records;  // record positions (Fig. 3)
    FrameStats stats;
};

LocalizedFrame render_localized(const FrameContext& context, const StaticSolution& solution,
                                const LocalizedSettings& settings);

}  // namespace steadylight
