// What the pixel centres' rays of a still view see with the dynamic objects left out: a function
// of the segment (its camera, static geometry and static cache), found by the first frame that
// asks and kept for the others. A frame needs a pixel centre's point twice, for the influence
// (every few pixels) and for L_y's records (every pixel, to tell where it wants one); where the
// ray meets no dynamic object before its static hit (RayTracer::meets_dynamic, the frame's own
// intersection's decision) and its point is not found through mirrors or glass, the point is
// the kept one, and the frame asks the dynamic objects alone, bit for bit the same answer.
#pragma once

#include <cstdint>
#include <mutex>
#include <optional>
#include <vector>

#include "steadylight/irradiance/irradiance_cache.h"
#include "steadylight/passes/sample_grid.h"
#include "steadylight/shading/frame_context.h"

namespace steadylight {

class KeptCentreRays {
public:
    /// An influence sample's point and the static irradiance there.
    struct Sample {
        Vec3 p;
        float reference = 0;  // the largest channel of the static cache's irradiance at p; 0: none
        bool seen = false;    // a diffuse point, p (else the centre sees none)
    };

    /// Makes them for `context`'s view, influence samples every `step`-th pixel centre, once
    /// (thread-safe; later calls must be for the same view and step).
    void make(const FrameContext& context, const IrradianceCache& static_cache, int step) const;

    /// Whether pixel (x, y)'s centre sees in `context`'s frame (of the view it was made for)
    /// what it sees with the dynamic objects left out, directly: then its point (cache_point_at)
    /// lies on a static object or is none, and is the kept one.
    bool sees_static_directly(const FrameContext& context, int x, int y) const;
    /// The same answer, with a ray only where `near_dynamic` (pixels_near_dynamic) says the
    /// centre's ray may pass through a dynamic object's bounds: elsewhere it cannot meet one.
    bool sees_static_directly(const FrameContext& context, int x, int y,
                              const std::vector<uint8_t>& near_dynamic) const;
    /// Influence sample i (of SampleGrid's order) where sees_static_directly.
    const Sample& sample(size_t i) const { return m_samples[i]; }

private:
    mutable std::once_flag m_once;
    // Per pixel, row by row: where its centre's ray first meets a static object (infinity:
    // none); negative where its point is found through mirrors or glass.
    mutable std::vector<float> m_static_t;
    mutable std::vector<Sample> m_samples;  // per sample of m_grid
    mutable SampleGrid m_grid;
};

/// The static indirect irradiance the influence is measured against at (p, n): its largest
/// channel, 0 where the static cache has none.
float influence_reference(const IrradianceCache& static_cache, Vec3 p, Vec3 n);

}  // namespace steadylight
