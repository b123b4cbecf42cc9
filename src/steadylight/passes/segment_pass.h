// The segment pass of the localized method (paper §3, §3.2; docs/design.md), once per segment:
// the static photons — the photon paths of the scene with its dynamic objects removed — and,
// by final gathering against them, the static irradiance cache over every distinct camera view
// of the segment (the camera path is known in advance). Every frame of the segment starts from
// it (frame_pass.h). Saving and loading it is segment_cache.h's business.
#pragma once

#include <cstdint>

#include "steadylight/irradiance/irradiance_cache.h"
#include "steadylight/passes/photon_mapping_settings.h"
#include "steadylight/photons/photon_paths.h"
#include "steadylight/scene/scene.h"
#include "steadylight/trace/ray_tracer.h"

namespace steadylight {

/// A hash of everything the static cache of `segment` depends on: the static objects and their
/// materials, the lights as they are at the segment's start (emissions and intensities
/// included), every camera view, and the settings that shape the cache.
uint64_t static_inputs_hash(const Scene& scene, const Segment& segment, const PhotonMappingSettings& settings);

/// The static irradiance cache of `segment`: static photons, then records over every distinct
/// camera view. Moves `tracer` through the segment's frames. With `paths` (the segment's static
/// photon paths, traced with settings.photons) their global map serves as the static photons.
IrradianceCache run_segment_pass(const Scene& scene, RayTracer& tracer, const Segment& segment,
                                 const PhotonMappingSettings& settings, const StaticPhotonPaths* paths = nullptr);

/// The first frame of each distinct camera view of the segment, in frame order.
std::vector<int> distinct_views(const Scene& scene, const Segment& segment);

/// The static photon paths of `segment` (photon_paths.h), which its frames compose their
/// photon maps from instead of tracing them all, with the irradiance at their global photons
/// (computed as needed; the static pass computes them all). `scene` and `tracer` must outlive
/// the paths. Moves `tracer` to the segment's first frame.
std::shared_ptr<const StaticPhotonPaths> trace_segment_photon_paths(const Scene& scene, RayTracer& tracer,
                                                                    const Segment& segment,
                                                                    const PhotonMappingSettings& settings);

}  // namespace steadylight
