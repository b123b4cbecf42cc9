#include "steadylight/irradiance/cache_builder.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <cmath>
#include <vector>

namespace steadylight {
namespace {

// A synthetic 64 x 48 "image" of the plane z = 0, one pixel per 0.01 units, with a patch of sky
// (no point) in one corner and a virtual wall at x = 0.32 that records near it see close by.
constexpr int width = 64, height = 48;
constexpr float footprint = 0.01f;
constexpr float wall_x = 0.32f;
constexpr int rays_per_gather = 128;
constexpr Vec3 up{0, 0, 1};

bool is_sky(int x, int y) { return x >= 56 && y < 8; }

std::optional<CachePoint> synthetic_point(int x, int y) {
    if (is_sky(x, y)) return std::nullopt;
    return CachePoint{{(float(x) + 0.5f) * footprint, (float(y) + 0.5f) * footprint, 0}, up, up, footprint};
}

/// A record with smooth irradiance and the distance to the wall as its harmonic mean distance.
GatherResult synthetic_gather(const CachePoint& point, uint64_t) {
    GatherResult result;
    const float E = 1 + point.p.x + 0.5f * std::sin(10 * point.p.y);
    result.record.p = point.p;
    result.record.n = point.n;
    result.record.E = {E, 2 * E, 0.5f * E};
    const Vec3 gradient{1, 5 * std::cos(10 * point.p.y), 0};
    result.record.translational_gradient = {gradient, gradient * 2, gradient * 0.5f};
    result.record.radius = std::abs(point.p.x - wall_x) + 0.001f;
    result.min_distance = result.record.radius;
    result.rays = rays_per_gather;
    return result;
}

struct Build {
    IrradianceCache cache;
    CacheBuildStats stats;
};

Build build(float accuracy = 0.25f) {
    Build b{IrradianceCache(CacheSettings{accuracy}), {}};
    b.stats = build_cache_over_image(b.cache, width, height, synthetic_point, synthetic_gather);
    return b;
}

/// The pixel index of a record's position in the synthetic image.
int pixel_of(const IrradianceRecord& record) {
    return int(record.p.y / footprint) * width + int(record.p.x / footprint);
}

TEST(CacheBuilder, CountsTheRecordsItAddsAndTheirRays) {
    const Build b = build();
    EXPECT_GT(b.stats.records_added, 0);
    EXPECT_EQ(b.stats.records_added, long(b.cache.records().size()));
    EXPECT_EQ(b.stats.gather_rays, b.stats.records_added * rays_per_gather);
}

TEST(CacheBuilder, LooksAtEveryPixelOnceAndGathersOnlyWherePointsAre) {
    std::vector<std::atomic<int>> looks(width * height);
    std::atomic<int> bad_ids = 0;
    IrradianceCache cache;
    build_cache_over_image(
        cache, width, height,
        [&](int x, int y) {
            ++looks[size_t(y * width + x)];
            return synthetic_point(x, y);
        },
        [&](const CachePoint& point, uint64_t id) {
            const int x = int(id % width), y = int(id / width);
            if (is_sky(x, y) || synthetic_point(x, y)->p != point.p) ++bad_ids;
            return synthetic_gather(point, id);
        });
    for (const std::atomic<int>& count : looks) EXPECT_EQ(count.load(), 1);
    EXPECT_EQ(bad_ids.load(), 0);
}

TEST(CacheBuilder, InsertsEachLevelInPixelOrder) {
    // 64 x 48 starts at spacing 8 (the largest power of two <= 48 / 4): levels 8, 4, 2, 1. Pixel
    // indices of the records rise within a level, so they can fall at most three times.
    const Build b = build();
    EXPECT_EQ(pixel_of(b.cache.records().front()), 0);
    int falls = 0;
    for (size_t i = 1; i < b.cache.records().size(); ++i)
        falls += pixel_of(b.cache.records()[i]) < pixel_of(b.cache.records()[i - 1]);
    EXPECT_LE(falls, 3);
}

TEST(CacheBuilder, AlmostEveryPixelIsCoveredAfterTheBuild) {
    // Neighbour clamping may shrink a record after it covered a pixel; the renderer gathers
    // afresh there. It must stay rare.
    const Build b = build();
    int pixels = 0, uncovered = 0;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::optional<CachePoint> point = synthetic_point(x, y);
            if (!point) continue;
            ++pixels;
            uncovered += !b.cache.covers(point->p, point->n);
        }
    }
    EXPECT_LE(uncovered, pixels / 100) << uncovered << " of " << pixels;
}

TEST(CacheBuilder, RecordsAreDenserNearTheWallAndRadiiStayClamped) {
    const Build b = build();
    int near = 0, far = 0;
    for (const IrradianceRecord& record : b.cache.records()) {
        EXPECT_GE(record.radius, 2 * footprint * (1 - 1e-6f));
        EXPECT_LE(record.radius, 32 * footprint * (1 + 1e-6f));
        near += std::abs(record.p.x - wall_x) < 0.08f;
        far += record.p.x < 0.16f;  // a strip of the same width, far from the wall
    }
    EXPECT_GT(near, 2 * far);
}

TEST(CacheBuilder, LargerAccuracyValueGivesFewerRecords) {
    const size_t fine = build(0.15f).cache.records().size();
    const size_t medium = build(0.3f).cache.records().size();
    const size_t coarse = build(0.6f).cache.records().size();
    EXPECT_GT(fine, medium);
    EXPECT_GT(medium, coarse);
}

TEST(CacheBuilder, AlreadyCoveredImageNeedsNoGathers) {
    IrradianceCache cache;
    IrradianceRecord big;
    big.p = {0.32f, 0.24f, 0};
    big.n = up;
    big.radius = 10;
    cache.insert(big);
    std::atomic<int> gathers = 0;
    const CacheBuildStats stats =
        build_cache_over_image(cache, width, height, synthetic_point, [&](const CachePoint& point, uint64_t id) {
            ++gathers;
            return synthetic_gather(point, id);
        });
    EXPECT_EQ(stats.records_added, 0);
    EXPECT_EQ(gathers.load(), 0);
    EXPECT_EQ(cache.records().size(), 1u);
}

TEST(CacheBuilder, TinyImageGetsOneRecord) {
    IrradianceCache cache;
    const CacheBuildStats stats = build_cache_over_image(cache, 1, 1, synthetic_point, synthetic_gather);
    EXPECT_EQ(stats.records_added, 1);
    EXPECT_EQ(cache.records().front().p, synthetic_point(0, 0)->p);
}

bool same_record(const IrradianceRecord& a, const IrradianceRecord& b) {
    return a.p == b.p && a.n == b.n && a.E == b.E && a.radius == b.radius &&
           a.rotational_gradient == b.rotational_gradient && a.translational_gradient == b.translational_gradient;
}

TEST(CacheBuilder, BuildIsTheSameInOneAndTwoThreads) {
    Build one, two;
    tbb::task_arena(1).execute([&] { one = build(); });
    tbb::task_arena(2).execute([&] { two = build(); });
    ASSERT_EQ(one.cache.records().size(), two.cache.records().size());
    for (size_t i = 0; i < one.cache.records().size(); ++i)
        EXPECT_TRUE(same_record(one.cache.records()[i], two.cache.records()[i])) << "record " << i;
    EXPECT_EQ(one.stats.gather_rays, two.stats.gather_rays);
}

}  // namespace
}  // namespace steadylight
