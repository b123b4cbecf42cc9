// What a still view's pixel centres see (centre_rays.h).
#include "steadylight/passes/centre_rays.h"

#include "steadylight/base/check.h"
#include "steadylight/base/parallel.h"
#include "steadylight/passes/photon_gather.h"
#include "steadylight/passes/pixel_reuse.h"

namespace steadylight {

float influence_reference(const IrradianceCache& static_cache, Vec3 p, Vec3 n) {
    const std::optional<Rgb> E = static_cache.interpolate(p, n, 2);
    return E ? max_component(*E) : 0.0f;
}

void KeptCentreRays::make(const FrameContext& context, const IrradianceCache& static_cache, int step) const {
    const Camera& camera = context.frame.camera;
    std::call_once(m_once, [&] {
        m_grid = {camera.width, camera.height, step};
        m_static_t.assign(size_t(camera.width) * size_t(camera.height), 0.0f);
        m_samples.assign(m_grid.size(), {});
        parallel_for_chunks(camera.height, 4, [&](long begin, long end) {
            for (int y = int(begin); y < int(end); ++y)
                for (int x = 0; x < camera.width; ++x) {
                    CentrePath path;
                    const std::optional<CachePoint> point =
                        cache_point_at(context, Visibility::static_only, x, y, &path);
                    float& static_t = m_static_t[size_t(y) * size_t(camera.width) + size_t(x)];
                    if (path.bounces > 0) {
                        static_t = -1;
                        continue;
                    }
                    static_t = path.first_t;
                    if (point && x % step == 0 && y % step == 0)
                        m_samples[m_grid.at(x, y)] = {point->p, influence_reference(static_cache, point->p, point->n),
                                                      true};
                }
        });
    });
    SL_CHECK(m_grid.width == camera.width && m_grid.height == camera.height && m_grid.step == step);
}

bool KeptCentreRays::sees_static_directly(const FrameContext& context, int x, int y) const {
    const float static_t = m_static_t[size_t(y) * size_t(m_grid.width) + size_t(x)];
    return static_t >= 0 &&
           !context.tracer.meets_dynamic(context.frame.camera.generate_ray(float(x) + 0.5f, float(y) + 0.5f), static_t);
}

bool KeptCentreRays::sees_static_directly(const FrameContext& context, int x, int y,
                                          const std::vector<uint8_t>& near_dynamic) const {
    const size_t i = size_t(y) * size_t(m_grid.width) + size_t(x);
    return near_dynamic[i] ? sees_static_directly(context, x, y) : m_static_t[i] >= 0;
}

}  // namespace steadylight
