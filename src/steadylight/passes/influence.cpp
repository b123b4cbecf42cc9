// The influence estimate and the blend weight (influence.h).
#include "steadylight/passes/influence.h"

#include <algorithm>

#include "steadylight/base/parallel.h"
#include "steadylight/passes/photon_gather.h"

namespace steadylight {
namespace {

/// I relative to `reference()` at p (asked only where some dynamic photon is near).
template <class Reference>
float relative_influence(const PhotonMap& dynamic, const LocalizedSettings& settings, float max_radius, Vec3 p,
                         Reference&& reference) {
    thread_local std::vector<Neighbour> neighbours;
    // Most of the image lies far from every dynamic photon: one nearest look-up tells.
    dynamic.k_nearest(p, 1, max_radius, neighbours);
    if (neighbours.empty()) return 0;
    // The sum needs a fixed order, not the nearest first: sorting the photons found took as
    // long as finding them.
    dynamic.k_nearest(p, settings.influence_photons, max_radius, neighbours, PointIndex::Order::farthest_first);
    float sum = 0;
    for (const Neighbour& nb : neighbours) {
        const Rgb& power = dynamic.photons()[nb.index].power;
        sum += std::max({std::abs(power.r), std::abs(power.g), std::abs(power.b)});
    }
    const float r2 =
        int(neighbours.size()) < settings.influence_photons ? max_radius * max_radius : neighbours.front().distance2;
    const float influence = sum / (pi * r2);
    // Scale-free: compare with the static indirect irradiance (or, where there is none, with
    // the influence itself, which then counts as large).
    const float E = reference();
    return E > 0 ? influence / E : (influence > 0 ? infinity : 0.0f);
}

}  // namespace

int influence_step(const LocalizedSettings& settings, int height) {
    return settings.influence_step > 0 ? settings.influence_step : 4 * std::max(1, height / 480);
}

InfluenceMap estimate_influence(const FrameContext& context, const PhotonMap& dynamic,
                                const IrradianceCache& static_cache, const LocalizedSettings& settings,
                                float search_radius, const KeptCentreRays* kept) {
    const Camera& camera = context.frame.camera;
    InfluenceMap map{{camera.width, camera.height, influence_step(settings, camera.height)}, {}};
    const SampleGrid& grid = map.grid;
    map.values.assign(grid.size(), 0.0f);
    if (dynamic.size() == 0) return map;
    parallel_for_chunks(long(map.values.size()), 64, [&](long begin, long end) {
        for (long i = begin; i < end; ++i) {
            const int x = grid.x(size_t(i)), y = grid.y(size_t(i));
            float& value = map.values[size_t(i)];
            if (kept && kept->sees_static_directly(context, x, y)) {
                const KeptCentreRays::Sample& sample = kept->sample(size_t(i));
                if (sample.seen)
                    value = relative_influence(dynamic, settings, search_radius, sample.p,
                                               [&] { return sample.reference; });
                continue;
            }
            const std::optional<CachePoint> point = cache_point_at(context, Visibility::everything, x, y);
            if (point)
                value = relative_influence(dynamic, settings, search_radius, point->p,
                                           [&] { return influence_reference(static_cache, point->p, point->n); });
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
