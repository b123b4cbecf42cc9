// The frame pass of the localized method (paper §3.1-§3.3; docs/design.md), each frame, from the
// segment's static solution (segment_cache.h):
//   photons in the complete scene (global, caustic and dynamic maps; frame_photons.h) ->
//   influence I of the dynamic objects per pixel (influence.h) -> L_y, a dynamic cache built
//   only where I > tau_l and on dynamic objects -> L_t, the static records corrected by the
//   dynamic map -> L_i = smoothstep blend of L_y and L_t -> L_d + L_i + L_c + L_s (shading_pass.h).
// StaticCacheUse::frozen is the cheap production practice it is compared with: the static
// cache as it is for static points, and L_y on dynamic objects only.
#pragma once

#include <memory>
#include <optional>

#include "steadylight/base/image.h"
#include "steadylight/passes/frame_stats.h"
#include "steadylight/passes/localized_settings.h"
#include "steadylight/passes/photon_mapping_settings.h"
#include "steadylight/passes/segment_cache.h"
#include "steadylight/shading/frame_context.h"

namespace steadylight {

/// How a frame uses the static cache at points off the dynamic objects.
enum class StaticCacheUse {
    corrected,  // the localized method: L_t (corrected records) blended with L_y by the influence
    frozen,     // the frozen baseline: the static records as they are
};

struct LocalizedFrame {
    Image beauty, direct, indirect, caustic, specular;
    std::optional<Image> alpha;  // with a transparent background (ShadedFrame::alpha)
    Image indirect_static;       // L_i from the static cache alone (paper Fig. 1d)
    Image L_y, L_t;              // the two estimates, as radiance (Fig. 1e, 1f)
    GreyImage influence;         // I relative to the static indirect irradiance (Fig. 4d, 5), at most 1000
    GreyImage dynamic;           // the share of a pixel's camera rays that see a dynamic object
    GreyImage static_records, dynamic_records;  // record positions (Fig. 3)
    GreyImage changed;  // with a static frame: the ChangedTerm bits of the terms redone (pixel_reuse.h)
    FrameStats stats;
};

/// The static frame of pixel reuse (pixel_reuse.h): `context`'s view shaded with the dynamic
/// objects removed, from the segment's static cache and photon paths (which must be there); none
/// when it would take more than `max_bytes`. Its frames must ask for the same analysis layers.
std::optional<StaticFrame> make_static_frame(const FrameContext& context, const StaticSolution& solution,
                                             const PhotonMappingSettings& photon, const LocalizedSettings& localized,
                                             double max_bytes, AnalysisLayers analysis = AnalysisLayers::made);

/// The static frame of a segment whose camera stands still, when it fits in
/// static_frame_memory_share of `available_bytes` (pixel_reuse.h): refused up front when the
/// part every pixel takes would not, and dropped when it grows past it while it is made; else
/// null, with a log line saying why (frames then shade every pixel).
std::shared_ptr<const StaticFrame> segment_static_frame(const Scene& scene, RayTracer& tracer, const Segment& segment,
                                                        const StaticSolution& solution,
                                                        const PhotonMappingSettings& photon,
                                                        const LocalizedSettings& localized, double available_bytes,
                                                        AnalysisLayers analysis = AnalysisLayers::made);

/// One frame; with the solution's static frame, when its view and lights are this frame's, only
/// the pixels the dynamic objects can change are shaded again (not for StaticCacheUse::frozen).
/// With AnalysisLayers::left_out the frame's layers after the four terms are left empty.
LocalizedFrame run_frame_pass(const FrameContext& context, const StaticSolution& solution,
                              const PhotonMappingSettings& photon, const LocalizedSettings& localized,
                              StaticCacheUse use, AnalysisLayers analysis = AnalysisLayers::made);

}  // namespace steadylight
