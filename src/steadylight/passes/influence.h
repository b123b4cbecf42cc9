// The influence of the dynamic objects on each pixel (paper §3.3; docs/design.md): a density
// estimate of the absolute power of the N nearest dynamic photons at the point a pixel's centre
// sees, relative to the static indirect irradiance there, and the smoothstep blend weight of
// L_y against L_t that it gives.
#pragma once

#include <vector>

#include "steadylight/irradiance/irradiance_cache.h"
#include "steadylight/passes/centre_rays.h"
#include "steadylight/passes/localized_settings.h"
#include "steadylight/passes/sample_grid.h"
#include "steadylight/photons/photon_map.h"
#include "steadylight/shading/frame_context.h"

namespace steadylight {

/// The influence I relative to the static indirect irradiance, at every `step`-th pixel centre;
/// the pixels between take their block's value. Empty (no values) where nothing was estimated.
struct InfluenceMap {
    SampleGrid grid;
    std::vector<float> values;  // per sample of the grid

    float at(int x, int y) const { return values[grid.at(x, y)]; }
};

/// I at the pixels of the frame, from the frame's dynamic photons; `search_radius` bounds the
/// photon search (the global irradiance estimate's radius). `kept`, in a still view: what its
/// pixel centres see with the dynamic objects left out, made with influence_step.
InfluenceMap estimate_influence(const FrameContext& context, const PhotonMap& dynamic,
                                const IrradianceCache& static_cache, const LocalizedSettings& settings,
                                float search_radius, const KeptCentreRays* kept = nullptr);

/// f(g(I)) of paper §3.3: 0 below tau_lower, 1 above tau_upper, a smoothstep between.
float blend_weight(float influence, const LocalizedSettings& settings);

}  // namespace steadylight
