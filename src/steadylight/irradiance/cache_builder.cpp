// Coarse-to-fine placement of irradiance records over an image (see cache_builder.h). Every
// parallel phase writes only to its own slot of a vector indexed by candidate, and the cache
// changes only between phases, in pixel order, so the records do not depend on the thread count.
// Both callbacks are called from several threads at once and must be thread-safe.
#include "steadylight/irradiance/cache_builder.h"

#include <algorithm>
#include <mutex>
#include <utility>
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

/// The pixels of the image first visited at `spacing`, in pixel order, whose points need
/// irradiance the cache does not cover yet: multiples of `spacing` that are not multiples of the
/// coarser level's spacing (2 * spacing), unless this is the coarsest level.
std::vector<Candidate> find_uncovered(const IrradianceCache& cache, int width, int height, int spacing, bool coarsest,
                                      const std::function<std::optional<CachePoint>(int, int)>& point_at) {
    // Each range of rows keeps its uncovered pixels in pixel order (few, where a frame places
    // L_y near a moving object: a slot per pixel was a frame's largest allocation at production
    // sizes); the ranges are then joined in order.
    std::mutex mutex;
    std::vector<std::pair<long, std::vector<Candidate>>> ranges;  // each range's first row and its candidates
    const long rows = (height + spacing - 1) / spacing;
    const long rows_per_chunk = std::max(1L, points_per_chunk * spacing / width);
    parallel_for_chunks(rows, rows_per_chunk, [&](long begin, long end) {
        std::vector<Candidate> found;
        for (long row = begin; row < end; ++row) {
            const int y = int(row) * spacing;
            // On the rows the coarser level visited, only the columns between its.
            const bool between = !coarsest && y % (2 * spacing) == 0;
            for (int x = between ? spacing : 0; x < width; x += between ? 2 * spacing : spacing) {
                const std::optional<CachePoint> point = point_at(x, y);
                if (point && !cache.covers(point->p, point->n)) found.push_back({{x, y}, *point});
            }
        }
        if (found.empty()) return;
        const std::lock_guard lock(mutex);
        ranges.emplace_back(begin, std::move(found));
    });
    std::sort(ranges.begin(), ranges.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<Candidate> candidates;
    for (const auto& [begin, found] : ranges) candidates.insert(candidates.end(), found.begin(), found.end());
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
        const std::vector<Candidate> candidates =
            find_uncovered(cache, width, height, spacing, spacing == coarsest, point_at);
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
