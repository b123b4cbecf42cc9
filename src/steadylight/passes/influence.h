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

/// The pixel step of the influence's samples in an image `height` pixels high: the setting's, or
/// where that is 0, 4 up to 959 rows and 4 more for every 480 rows beyond. The estimate's disc, 300
/// photons wide, does not shrink with the pixels, and every 4th pixel of 320x240 already samples
/// it finely; at 1280x960 every 8th pixel costs a quarter of every 4th and places the same L_y
/// records, while every 16th placed 13% more (a pixel takes its block's sample, so coarser blocks
/// reach farther from the moving object; docs/notes/frame-cost.md, step 20).
int influence_step(const LocalizedSettings& settings, int height);

/// I at the pixels of the frame, from the frame's dynamic photons; `search_radius` bounds the
/// photon search (the global irradiance estimate's radius). `kept`, in a still view: what its
/// pixel centres see with the dynamic objects left out, made with influence_step().
InfluenceMap estimate_influence(const FrameContext& context, const PhotonMap& dynamic,
                                const IrradianceCache& static_cache, const LocalizedSettings& settings,
                                float search_radius, const KeptCentreRays* kept = nullptr);

/// f(g(I)) of paper §3.3: 0 below tau_lower, 1 above tau_upper, a smoothstep between.
float blend_weight(float influence, const LocalizedSettings& settings);

}  // namespace steadylight
