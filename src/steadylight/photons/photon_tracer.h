// Photon tracing, the first pass of photon mapping (Jensen 2001, ch. 5): photons leave the lights
// in proportion to their power and bounce through the scene by the BSDFs, with Russian roulette
// by reflectance so that the power of surviving photons stays constant. Caustic photons are aimed
// at the specular and glossy objects (caustic_targets.h). Every random decision of
// photon i comes from point i of the scrambled Halton sequence (base/halton.h), so the photons
// of a frame depend only on the scene at that frame (paper §4).
//
// In a scene with dynamic objects the same pass also fills the dynamic photon map (paper §3.1,
// DESIGN.md §2.1): from a path's first dynamic hit on, its diffuse hits are stored there (except
// direct hits), and a negative photon re-traces the static path the photon would have taken
// without the dynamic objects, with the same random numbers, carrying negated power.
// photon_walk.h holds the walk itself; photon_paths.h composes a frame's maps from the static
// paths instead, with the same result.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "steadylight/photons/photon_map.h"
#include "steadylight/shading/frame_context.h"

namespace steadylight {

struct PhotonSettings {
    long global_photons = 200'000;   // photon paths emitted for the global map
    long caustic_photons = 200'000;  // photon paths emitted for the caustic map
    // Bounces before a path is cut, as the path tracer's max_depth: survival by the scattered
    // power ends nearly every path long before (16 cut a room of albedo 0.75 about 1% dark).
    int max_bounces = 64;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(PhotonSettings, global_photons, caustic_photons, max_bounces)
/// Throws InputError naming `where` + "/<field>" for a value out of range.
void validate(const PhotonSettings& settings, const std::string& where);

struct TracedPhotons {
    PhotonMap global;   // every diffuse hit, direct ones included (for final gathering)
    PhotonMap caustic;  // diffuse hits after one or more specular bounces (L S+ D)
    PhotonMap dynamic;  // the change the dynamic objects make: positive and negative photons
};

/// Traces both kinds of photons in the scene as `context.frame` places it, seeing the objects
/// that `visibility` allows; with Visibility::everything in a scene with dynamic objects it also
/// fills the dynamic map (from the global photons' paths). Deterministic: the maps are the same
/// for any thread count.
TracedPhotons trace_photons(const FrameContext& context, const PhotonSettings& settings,
                            Visibility visibility = Visibility::everything);

}  // namespace steadylight
