// The influence of the dynamic objects on each pixel (paper §3.3; docs/design.md): a density
// estimate of the absolute power of the N nearest dynamic photons at the point a pixel's centre
// sees, relative to the static indirect irradiance there, and the smoothstep blend weight of
// L_y against L_t that it gives.
#pragma once

#include <mutex>
#include <vector>

#include "steadylight/irradiance/irradiance_cache.h"
#include "steadylight/passes/localized_settings.h"
#include "steadylight/photons/photon_map.h"
#include "steadylight/shading/frame_context.h"

namespace steadylight {

/// The influence I relative to the static indirect irradiance, at every `step`-th pixel centre;
/// the pixels between take their block's value. Empty (no values) where nothing was estimated.
struct InfluenceMap {
    int width = 0, height = 0, step = 1;
    std::vector<float> values;  // (width / step rounded up) x (height / step rounded up)

    float at(int x, int y) const {
        const int columns = (width + step - 1) / step;
        return values[size_t((y / step) * columns + x / step)];
    }
};

/// What the influence samples of a still view see with the dynamic objects left out, and the
/// static cache's irradiance there: a function of the segment (its camera, static geometry and
/// static cache), found by the first frame that asks (thread-safe) and kept for the others, about
/// 1.5 bytes a pixel. A frame takes a sample's point from here wherever its pixel centre's ray
/// meets no dynamic object (RayTracer::meets_dynamic, the frame's own intersect's decision), so
/// its influence is bit for bit the one found anew, without the camera ray and the cache look-up.
class KeptInfluencePoints {
public:
    struct Sample {
        Vec3 p;
        float reference = 0;  // the largest channel of the static cache's irradiance at p; 0: none
        float static_t = 0;   // where the centre's ray meets the static objects (infinity: none)
        bool kept = false;    // false: found through mirrors or glass, anew in every frame
        bool seen = false;    // a diffuse point, p (else the sample sees none)
    };

    /// The samples of `context`'s view, row by row (InfluenceMap's order), made on first use.
    const std::vector<Sample>& samples(const FrameContext& context, const IrradianceCache& static_cache,
                                       const LocalizedSettings& settings) const;

private:
    mutable std::once_flag m_once;
    mutable std::vector<Sample> m_samples;
};

/// I at the pixels of the frame, from the frame's dynamic photons; `search_radius` bounds the
/// photon search (the global irradiance estimate's radius). `kept`, for a still view: where the
/// samples' points were found before.
InfluenceMap estimate_influence(const FrameContext& context, const PhotonMap& dynamic,
                                const IrradianceCache& static_cache, const LocalizedSettings& settings,
                                float search_radius, const KeptInfluencePoints* kept = nullptr);

/// f(g(I)) of paper §3.3: 0 below tau_lower, 1 above tau_upper, a smoothstep between.
float blend_weight(float influence, const LocalizedSettings& settings);

}  // namespace steadylight
