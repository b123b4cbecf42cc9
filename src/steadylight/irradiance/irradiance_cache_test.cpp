#include "steadylight/irradiance/irradiance_cache.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "steadylight/base/ray.h"
#include "steadylight/base/rng.h"

namespace steadylight {
namespace {

constexpr Vec3 up{0, 0, 1};

IrradianceRecord record_at(Vec3 p, Vec3 n, Rgb E, float radius) {
    IrradianceRecord record;
    record.p = p;
    record.n = n;
    record.E = E;
    record.radius = radius;
    return record;
}

/// A cache with Ward's a = 0.25 and the given records.
IrradianceCache cache_of(const std::vector<IrradianceRecord>& records, float accuracy = 0.25f) {
    IrradianceCache cache(CacheSettings{accuracy});
    for (const IrradianceRecord& record : records) cache.insert(record);
    return cache;
}

TEST(IrradianceCache, EmptyCacheCoversNothing) {
    const IrradianceCache cache;
    EXPECT_FALSE(cache.covers({0, 0, 0}, up));
    EXPECT_FALSE(cache.interpolate({0, 0, 0}, up));
    EXPECT_TRUE(cache.records().empty());
}

TEST(IrradianceCache, InterpolatingAtARecordReturnsItsIrradianceExactly) {
    IrradianceRecord a = record_at({0, 0, 0}, up, {1.0f, 2.0f, 3.0f}, 1.0f);
    IrradianceRecord b = record_at({0.1f, 0, 0}, normalize(Vec3{0.1f, 0, 1}), {1.3f, 2.7f, 0.1f}, 1.0f);
    a.translational_gradient = {Vec3{0.3f, 0, 0}, Vec3{0, 1, 0}, Vec3{-1, 0, 0}};
    b.rotational_gradient = {Vec3{0, 0.5f, 0}, Vec3{0.2f, 0, 0}, Vec3{0, 0, 0}};
    const IrradianceCache cache = cache_of({a, b});
    EXPECT_EQ(cache.interpolate(a.p, a.n), a.E);
    EXPECT_EQ(cache.interpolate(b.p, b.n), b.E);
    EXPECT_EQ(cache.records().size(), 2u);
}

TEST(IrradianceCache, RecordIsUsedOnlyWithinAccuracyTimesItsRadius) {
    // w = 1 / (d / R) > 1 / a  <=>  d < a R.
    const IrradianceCache cache = cache_of({record_at({1, 1, 0}, up, {1, 1, 1}, 2.0f)});
    EXPECT_TRUE(cache.covers({1.49f, 1, 0}, up));
    EXPECT_TRUE(cache.covers({1, 0.51f, 0}, up));
    EXPECT_FALSE(cache.covers({1.51f, 1, 0}, up));
    EXPECT_FALSE(cache.interpolate({1, 0.49f, 0}, up));
}

TEST(IrradianceCache, RecordIsNotUsedForTurnedOrOppositeNormals) {
    // At p_i the weight is 1 / sqrt(1 - n . n_i): used while n . n_i > 1 - a^2 = 0.9375.
    const IrradianceCache cache = cache_of({record_at({0, 0, 0}, up, {1, 1, 1}, 1.0f)});
    const auto tilted = [](float cos_theta) { return Vec3{std::sqrt(1 - cos_theta * cos_theta), 0, cos_theta}; };
    EXPECT_TRUE(cache.covers({0, 0, 0}, tilted(0.95f)));
    EXPECT_FALSE(cache.covers({0, 0, 0}, tilted(0.92f)));
    EXPECT_FALSE(cache.covers({0, 0, 0}, -up));
    EXPECT_FALSE(cache.covers({0.01f, 0, 0}, -up));
}

TEST(IrradianceCache, RecordInFrontOfThePointIsNotUsed) {
    // A record 0.1 above p (on a step's top, say) is within a R = 0.25 but lies in front of p.
    const IrradianceCache above = cache_of({record_at({0, 0, 0.1f}, up, {1, 1, 1}, 1.0f)});
    EXPECT_FALSE(above.covers({0, 0, 0}, up));
    const IrradianceCache below = cache_of({record_at({0, 0, -0.1f}, up, {1, 1, 1}, 1.0f)});
    EXPECT_TRUE(below.covers({0, 0, 0}, up));
}

TEST(IrradianceCache, InterpolationIsWardsWeightedMean) {
    const IrradianceRecord a = record_at({0, 0, 0}, up, {1, 2, 3}, 1.0f);
    const IrradianceRecord b = record_at({0.2f, 0, 0}, up, {3, 2, 1}, 2.0f);
    const Vec3 p{0.05f, 0.05f, 0};
    const float wa = 1 / (length(p - a.p) / a.radius), wb = 1 / (length(p - b.p) / b.radius);
    const std::optional<Rgb> E = cache_of({a, b}).interpolate(p, up);
    ASSERT_TRUE(E);
    const Rgb want = (a.E * wa + b.E * wb) / (wa + wb);
    EXPECT_NEAR(E->r, want.r, 1e-5f);
    EXPECT_NEAR(E->g, want.g, 1e-5f);
    EXPECT_NEAR(E->b, want.b, 1e-5f);
}

// Over its radius a record's translational gradient changes its irradiance by at most its own
// E: a steeper one is scaled to E / R (a crease's records had gradients 40 times that).
TEST(IrradianceCache, TranslationalGradientChangesARecordByAtMostItsIrradianceOverItsRadius) {
    IrradianceRecord record = record_at({0, 0, 0}, up, {1, 1, 1}, 1.0f);
    record.translational_gradient = {Vec3{-10, 0, 0}, Vec3{0, 0.5f, 0}, Vec3{2, 0, 0}};
    const std::optional<Rgb> E = cache_of({record}).interpolate({0.2f, 0.1f, 0}, up);
    ASSERT_TRUE(E);
    EXPECT_FLOAT_EQ(E->r, 0.8f);   // -10 scaled to -1: 1 - 0.2
    EXPECT_FLOAT_EQ(E->g, 1.05f);  // 0.5 R is less than E: as it is
    EXPECT_FLOAT_EQ(E->b, 1.2f);   // 2 scaled to 1
    EXPECT_FLOAT_EQ(cache_of({record}).interpolate({-0.2f, 0, 0}, up)->r, 1.2f);
}

// With the rotational gradient as well, the change stays within [0, 2 E].
TEST(IrradianceCache, ExtrapolatedIrradianceStaysBetweenZeroAndTwiceTheRecords) {
    IrradianceRecord record = record_at({0, 0, 0}, up, {1, 1, 1}, 1.0f);
    record.translational_gradient = {Vec3{-1, 0, 0}, Vec3{0, 0, 0}, Vec3{1, 0, 0}};
    record.rotational_gradient = {Vec3{0, -20, 0}, Vec3{0, 0, 0}, Vec3{0, 20, 0}};
    const Vec3 tilted = normalize(Vec3{0.1f, 0, 1});  // turn = up x tilted points along +y
    const std::optional<Rgb> E = cache_of({record}).interpolate({0.1f, 0, 0}, tilted);
    ASSERT_TRUE(E);
    EXPECT_EQ(E->r, 0.0f);
    EXPECT_FLOAT_EQ(E->g, 1.0f);
    EXPECT_FLOAT_EQ(E->b, 2.0f);
}

/// The same records with both gradients zeroed.
std::vector<IrradianceRecord> without_gradients(std::vector<IrradianceRecord> records) {
    for (IrradianceRecord& record : records) record.rotational_gradient = record.translational_gradient = {};
    return records;
}

/// The largest absolute error of interpolation along a path of (p, n) against `want`.
float max_error(const IrradianceCache& cache, int steps, const std::function<std::pair<Vec3, Vec3>(float)>& path,
                const std::function<float(Vec3, Vec3)>& want) {
    float error = 0;
    for (int i = 0; i <= steps; ++i) {
        const auto [p, n] = path(float(i) / float(steps));
        const std::optional<Rgb> E = cache.interpolate(p, n);
        EXPECT_TRUE(E);
        if (E) error = std::max(error, std::abs(E->g - want(p, n)));
    }
    return error;
}

TEST(IrradianceCache, TranslationalGradientsReproduceALinearFieldBetweenTwoRecords) {
    // E(x) = 1 + 0.5 x on the plane z = 0; records at x = 0 and x = 0.4, each valid to 0.5.
    const auto field = [](Vec3 p, Vec3) { return 1 + 0.5f * p.x; };
    std::vector<IrradianceRecord> records;
    for (const float x : {0.0f, 0.4f}) {
        IrradianceRecord record = record_at({x, 0, 0}, up, {}, 2.0f);
        record.E = {field(record.p, up), field(record.p, up), field(record.p, up)};
        record.translational_gradient = {Vec3{0.5f, 0, 0}, Vec3{0.5f, 0, 0}, Vec3{0.5f, 0, 0}};
        records.push_back(record);
    }
    const auto path = [](float t) { return std::pair{Vec3{-0.1f + 0.6f * t, 0.05f, 0}, up}; };
    EXPECT_LT(max_error(cache_of(records), 60, path, field), 1e-5f);
    EXPECT_GT(max_error(cache_of(without_gradients(records)), 60, path, field), 0.03f);
}

TEST(IrradianceCache, RotationalGradientsFollowIrradianceAroundACurvedSurface) {
    // On the unit sphere (p = n), sky radiance a + b . w gives E(n) = pi a + (2 pi / 3) b . n and the
    // rotational gradient (2 pi / 3) n_i x b (see final_gather_test.cpp). Records at two normals
    // 17 degrees apart; the path runs a little past both. First-order extrapolation leaves
    // (2 pi / 3) (b . n_i) (1 - n . n_i), small for a b nearly along the surface.
    const Vec3 b{0.8f, 0.1f, 0.05f};
    const auto field = [&](Vec3, Vec3 n) { return pi + 2 * pi / 3 * dot(b, n); };
    const auto normal_at = [](float t) { return normalize(Vec3{0.3f * t, 0, 1}); };
    std::vector<IrradianceRecord> records;
    for (const float t : {0.0f, 1.0f}) {
        const Vec3 n = normal_at(t);
        IrradianceRecord record = record_at(n, n, {}, 4.0f);
        record.E = {field(n, n), field(n, n), field(n, n)};
        const Vec3 gradient = cross(n, b) * (2 * pi / 3);
        record.rotational_gradient = {gradient, gradient, gradient};
        records.push_back(record);
    }
    const auto path = [&](float t) { return std::pair{normal_at(1.6f * t - 0.3f), normal_at(1.6f * t - 0.3f)}; };
    const float with = max_error(cache_of(records, 0.5f), 40, path, field);
    const float without = max_error(cache_of(without_gradients(records), 0.5f), 40, path, field);
    EXPECT_LT(with, 0.1f * without) << with << " vs " << without;
}

TEST(IrradianceCache, NeighbourClampingBoundsARadiusByANeighboursRadiusPlusDistance) {
    IrradianceCache cache =
        cache_of({record_at({0, 0, 0}, up, {1, 1, 1}, 10.0f), record_at({2, 0, 0}, up, {1, 1, 1}, 1.0f),
                  record_at({5, 0, 0}, up, {1, 1, 1}, 10.0f), record_at({100, 0, 0}, up, {1, 1, 1}, 10.0f)});
    EXPECT_TRUE(cache.covers({2.4f, 0, 0}, up));  // within a R = 2.5 of the first record
    cache.clamp_radii_to_neighbours();
    EXPECT_EQ(cache.records()[0].radius, 3.0f);
    EXPECT_EQ(cache.records()[1].radius, 1.0f);
    EXPECT_EQ(cache.records()[2].radius, 4.0f);
    EXPECT_EQ(cache.records()[3].radius, 10.0f);
    EXPECT_FALSE(cache.covers({2.4f, 0, 0}, up));  // the look-up sees the new radii
}

/// `count` random records on and near the square [0, 1]^2 of the plane z = 0, mostly facing up.
std::vector<IrradianceRecord> random_records(int count, uint64_t seed) {
    Pcg32 rng(seed);
    std::vector<IrradianceRecord> records;
    for (int i = 0; i < count; ++i) {
        const Vec3 p{rng.next_float(), rng.next_float(), 0.02f * rng.next_float()};
        const Vec3 n = normalize(Vec3{rng.next_float() - 0.5f, rng.next_float() - 0.5f, i % 10 == 0 ? -2.0f : 2.0f});
        const float radius = 0.02f * std::pow(20.0f, rng.next_float());  // 0.02 to 0.4
        IrradianceRecord record = record_at(p, n, {1 + rng.next_float(), 2 * rng.next_float(), 5.0f}, radius);
        record.translational_gradient[0] = Vec3{rng.next_float() - 0.5f, rng.next_float() - 0.5f, 0};
        records.push_back(record);
    }
    return records;
}

/// Ward's interpolation over every record, without any index, in double precision.
std::optional<Rgb> brute_force_interpolate(const std::vector<IrradianceRecord>& records, float accuracy, Vec3 p,
                                           Vec3 n) {
    double sum[3] = {0, 0, 0}, weight_sum = 0;
    for (const IrradianceRecord& r : records) {
        // Decide in float, as the cache does, so that records on the edge go the same way.
        const float cos_normals = dot(n, r.n);
        if (cos_normals <= 0 || dot(p - r.p, (n + r.n) * 0.5f) < -0.05f * r.radius) continue;
        const float weight = 1 / (length(p - r.p) / r.radius + length(n - r.n) * 0.70710678f);
        if (!(weight > 1 / accuracy)) continue;
        for (int c = 0; c < 3; ++c)
            sum[c] += weight * std::max(0.0f, r.E[c] + dot(cross(r.n, n), r.rotational_gradient[c]) +
                                                  dot(p - r.p, r.translational_gradient[c]));
        weight_sum += weight;
    }
    if (weight_sum == 0) return std::nullopt;
    return Rgb{float(sum[0] / weight_sum), float(sum[1] / weight_sum), float(sum[2] / weight_sum)};
}

TEST(IrradianceCache, IndexFindsTheSameRecordsAsBruteForce) {
    const float accuracy = 0.5f;
    const std::vector<IrradianceRecord> records = random_records(2000, 1);
    const IrradianceCache cache = cache_of(records, accuracy);
    const std::vector<IrradianceRecord> queries = random_records(2000, 2);
    int covered = 0;
    for (const IrradianceRecord& q : queries) {
        const std::optional<Rgb> want = brute_force_interpolate(records, accuracy, q.p, q.n);
        const std::optional<Rgb> got = cache.interpolate(q.p, q.n);
        ASSERT_EQ(got.has_value(), want.has_value());
        EXPECT_EQ(cache.covers(q.p, q.n), want.has_value());
        if (!want) continue;
        ++covered;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR((*got)[c], (*want)[c], 1e-4f * (1 + (*want)[c]));
    }
    EXPECT_GT(covered, 1000);  // the test looks at many overlapping records, not only misses
    // Relaxed look-ups (records reaching twice as far) read an index of their own.
    int covered_relaxed = 0;
    for (const IrradianceRecord& q : queries) {
        const std::optional<Rgb> want = brute_force_interpolate(records, 2 * accuracy, q.p, q.n);
        const std::optional<Rgb> got = cache.interpolate(q.p, q.n, 2);
        ASSERT_EQ(got.has_value(), want.has_value());
        if (!want) continue;
        ++covered_relaxed;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR((*got)[c], (*want)[c], 1e-4f * (1 + (*want)[c]));
    }
    EXPECT_GT(covered_relaxed, covered);
}

// L_t's corrected cache: the static records with other irradiance, on the static cache's index,
// answers as a cache built over them, bit for bit, also once the static cache is gone.
TEST(IrradianceCache, CacheWithOtherIrradianceAnswersAsOneBuiltOverItsRecords) {
    const std::vector<IrradianceRecord> records = random_records(2000, 1);
    std::vector<IrradianceRecord> changed = records;
    for (size_t i = 0; i < changed.size(); i += 3) changed[i].E = changed[i].E * 0.5f;
    auto base = std::make_unique<IrradianceCache>(cache_of(records, 0.5f));
    const IrradianceCache corrected = base->with_irradiance(changed);
    base.reset();
    const IrradianceCache built = cache_of(changed, 0.5f);
    int covered = 0;
    for (const IrradianceRecord& q : random_records(2000, 2))
        for (const float reach : {1.0f, 2.0f}) {
            const std::optional<Rgb> got = corrected.interpolate(q.p, q.n, reach);
            ASSERT_EQ(got, built.interpolate(q.p, q.n, reach));
            covered += got.has_value();
        }
    EXPECT_GT(covered, 1000);
}

TEST(IrradianceCache, NeighbourClampingMatchesBruteForce) {
    std::vector<IrradianceRecord> records = random_records(500, 3);
    IrradianceCache cache = cache_of(records);
    cache.clamp_radii_to_neighbours();
    for (size_t i = 0; i < records.size(); ++i) {
        float want = records[i].radius;
        for (const IrradianceRecord& other : records)
            want = std::min(want, other.radius + length(records[i].p - other.p));
        EXPECT_EQ(cache.records()[i].radius, want);
        EXPECT_EQ(cache.records()[i].p, records[i].p);  // same order
    }
}

TEST(IrradianceCache, MovedCacheKeepsItsRecordsAndIndex) {
    IrradianceCache cache = cache_of({record_at({0, 0, 0}, up, {1, 1, 1}, 1.0f)});
    const IrradianceCache moved = std::move(cache);
    EXPECT_TRUE(moved.covers({0.1f, 0, 0}, up));
    EXPECT_EQ(moved.records().size(), 1u);
}

// A record reaches a * R: the radius is clamped so that its reach spans [2, 32] pixels.
TEST(IrradianceCache, ClampRadiusKeepsTheReachBetweenPixelSpacings) {
    const CacheSettings settings{0.25f, 2.0f, 32.0f};
    EXPECT_FLOAT_EQ(clamp_radius(infinity, 0.01f, settings), 1.28f);
    EXPECT_FLOAT_EQ(clamp_radius(0.001f, 0.01f, settings), 0.08f);
    EXPECT_FLOAT_EQ(clamp_radius(0.1f, 0.01f, settings), 0.1f);
}

}  // namespace
}  // namespace steadylight
