// Coarse-to-fine placement of irradiance records over an image (see cache_builder.h). Every
// parallel phase writes only to its own slot of a vector indexed by candidate, and the cache
// changes only between phases, in pixel order, so the records do not depend on the thread count.
// Both callbacks are called from several threads at once and must be thread-safe.
#include "steadylight/irradiance/cache_builder.h"

#include <algorithm>
#include <vector>

#include "steadylight/base/check.h"
#include "steadylight/base/parallel.h"

namespace steadylight {
namespace {

constexpr long points_per_chunk = 256;  // cheap work: a camera ray and a cache look-up
constexpr long gathers_per_chunk = 4;   // expensive work: hundreds of rays each

struct Pixel {
    int x, y;
};

struct Candidate {
    Pixel pixel;
    CachePoint point;
};

/// The coarsest grid spacing: the largest power of two <= min(width, height) / 4, at least 1.
int coarsest_spacing(int width, int height) {
    int spacing = 1;
    while (spacing * 2 <= std::min(width, height) / 4) spacing *= 2;
    return spacing;
}

/// The pixels first visited at `spacing`, in pixel order: multiples of `spacing` that are not
/// multiples of the coarser level's spacing (2 * spacing), unless this is the coarsest level.
std::vector<Pixel> level_pixels(int width, int height, int spacing, bool coarsest) {
    std::vector<Pixel> pixels;
    for (int y = 0; y < height; y += spacing) {
        for (int x = 0; x < width; x += spacing) {
            const bool visited = !coarsest && x % (2 * spacing) == 0 && y % (2 * spacing) == 0;
            if (!visited) pixels.push_back({x, y});
        }
    }
    return pixels;
}

/// The pixels whose points need irradiance the cache does not cover yet, in pixel order.
std::vector<Candidate> find_uncovered(const IrradianceCache& cache, const std::vector<Pixel>& pixels,
                                      const std::function<std::optional<CachePoint>(int, int)>& point_at) {
    // Look up every pixel's point and test it against the cache, each into its own slot.
    std::vector<std::optional<CachePoint>> needed(pixels.size());
    parallel_for_chunks(long(pixels.size()), points_per_chunk, [&](long begin, long end) {
        for (long i = begin; i < end; ++i) {
            const std::optional<CachePoint> point = point_at(pixels[size_t(i)].x, pixels[size_t(i)].y);
            if (point && !cache.covers(point->p, point->n)) needed[size_t(i)] = point;
        }
    });

    // Keep the uncovered ones, in pixel order.
    std::vector<Candidate> candidates;
    for (size_t i = 0; i < pixels.size(); ++i)
        if (needed[i]) candidates.push_back({pixels[i], *needed[i]});
    return candidates;
}

/// Gathers a record at every candidate, in parallel, each into its own slot.
std::vector<GatherResult> gather_candidates(const std::vector<Candidate>& candidates, int width,
                                            const std::function<GatherResult(const CachePoint&, uint64_t)>& gather) {
    std::vector<GatherResult> results(candidates.size());
    parallel_for_chunks(long(candidates.size()), gathers_per_chunk, [&](long begin, long end) {
        for (long i = begin; i < end; ++i) {
            const Candidate& c = candidates[size_t(i)];
            results[size_t(i)] = gather(c.point, uint64_t(c.pixel.y) * uint64_t(width) + uint64_t(c.pixel.x));
        }
    });
    return results;
}

}  // namespace

CacheBuildStats build_cache_over_image(IrradianceCache& cache, int width, int height,
                                       const std::function<std::optional<CachePoint>(int x, int y)>& point_at,
                                       const std::function<GatherResult(const CachePoint&, uint64_t id)>& gather) {
    SL_CHECK(width > 0 && height > 0);
    CacheBuildStats stats;
    const int coarsest = coarsest_spacing(width, height);
    for (int spacing = coarsest; spacing >= 1; spacing /= 2) {
        // Find this level's uncovered points against the cache as the previous level left it.
        const std::vector<Pixel> pixels = level_pixels(width, height, spacing, spacing == coarsest);
        const std::vector<Candidate> candidates = find_uncovered(cache, pixels, point_at);
        if (candidates.empty()) continue;

        // Gather them all, then insert in pixel order with radii clamped to the pixel footprint.
        const std::vector<GatherResult> results = gather_candidates(candidates, width, gather);
        for (size_t i = 0; i < candidates.size(); ++i) {
            IrradianceRecord record = results[i].record;
            record.radius = clamp_radius(record.radius, candidates[i].point.pixel_footprint, cache.settings());
            cache.insert(record);
            stats.gather_rays += results[i].rays;
        }
        stats.records_added += long(candidates.size());

        // Spread small radii to the neighbours (Krivanek et al. 2006) before the next level looks.
        cache.clamp_radii_to_neighbours();
    }
    return stats;
}

}  // namespace steadylight
