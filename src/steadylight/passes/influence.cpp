// The influence estimate and the blend weight (influence.h).
#include "steadylight/passes/influence.h"

#include <algorithm>

#include "steadylight/base/parallel.h"
#include "steadylight/passes/photon_gather.h"

namespace steadylight {
namespace {

float relative_influence(const FrameContext& context, const PhotonMap& dynamic, const IrradianceCache& static_cache,
                         const LocalizedSettings& settings, float max_radius, int x, int y) {
    const std::optional<CachePoint> point = cache_point_at(context, Visibility::everything, x, y);
    if (!point) return 0;
    thread_local std::vector<Neighbour> neighbours;
    // Most of the image lies far from every dynamic photon: one nearest look-up tells.
    dynamic.k_nearest(point->p, 1, max_radius, neighbours);
    if (neighbours.empty()) return 0;
    dynamic.k_nearest(point->p, settings.influence_photons, max_radius, neighbours);
    float sum = 0;
    for (const Neighbour& nb : neighbours) {
        const Rgb& power = dynamic.photons()[nb.index].power;
        sum += std::max({std::abs(power.r), std::abs(power.g), std::abs(power.b)});
    }
    const float r2 =
        int(neighbours.size()) < settings.influence_photons ? max_radius * max_radius : neighbours.back().distance2;
    const float influence = sum / (pi * r2);
    const std::optional<Rgb> E = static_cache.interpolate(point->p, point->n, 2);
    // Scale-free: compare with the static indirect irradiance (or, where there is none, with
    // the influence itself, which then counts as large).
    const float reference = E ? max_component(*E) : 0.0f;
    return reference > 0 ? influence / reference : (influence > 0 ? infinity : 0.0f);
}

}  // namespace

InfluenceMap estimate_influence(const FrameContext& context, const PhotonMap& dynamic,
                                const IrradianceCache& static_cache, const LocalizedSettings& settings,
                                float search_radius) {
    const Camera& camera = context.frame.camera;
    InfluenceMap map{camera.width, camera.height, settings.influence_step, {}};
    const int columns = (camera.width + map.step - 1) / map.step, rows = (camera.height + map.step - 1) / map.step;
    map.values.assign(size_t(columns * rows), 0.0f);
    if (dynamic.size() == 0) return map;
    parallel_for_chunks(long(map.values.size()), 64, [&](long begin, long end) {
        for (long i = begin; i < end; ++i) {
            const int x = int(i % columns) * map.step, y = int(i / columns) * map.step;
            map.values[size_t(i)] = relative_influence(context, dynamic, static_cache, settings, search_radius, x, y);
        }
    });
    return map;
}

float blend_weight(float influence, const LocalizedSettings& settings) {
    const float x =
        std::clamp((influence - settings.tau_lower) / (settings.tau_upper - settings.tau_lower), 0.0f, 1.0f);
    return x * x * (3 - 2 * x);
}

}  // namespace steadylight
