// Placing irradiance records over an image, coarse to fine and deterministically: at each level
// (grid spacing 2^k pixels down to 1), the grid pixels whose surface point is not yet covered by
// the cache are gathered in parallel against the cache as it stood after the previous level, and
// the new records are inserted in pixel order. The result does not depend on thread count or
// scheduling.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>

#include "steadylight/irradiance/final_gather.h"
#include "steadylight/irradiance/irradiance_cache.h"

namespace steadylight {

/// The surface point whose indirect diffuse irradiance a pixel needs.
struct CachePoint {
    Vec3 p;
    Vec3 n;                     // unit shading normal, facing the viewer
    Vec3 ng;                    // unit geometric normal, same side as n
    float pixel_footprint = 0;  // world-space size of one pixel at p
    int object = -1;            // the object the point lies on
};

struct CacheBuildStats {
    long records_added = 0;
    long gather_rays = 0;
};

/// Adds records to `cache` until every pixel's point (from `point_at`, std::nullopt where the
/// pixel needs no irradiance) is covered. `gather(point, id)` computes a record (radius unclamped);
/// `id` is the pixel index, for seeding. Both callbacks are called from several threads at once.
CacheBuildStats build_cache_over_image(IrradianceCache& cache, int width, int height,
                                       const std::function<std::optional<CachePoint>(int x, int y)>& point_at,
                                       const std::function<GatherResult(const CachePoint&, uint64_t id)>& gather);

}  // namespace steadylight
