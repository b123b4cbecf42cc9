#include "steadylight/photons/photon_map.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "steadylight/base/halton.h"
#include "steadylight/base/rng.h"

namespace steadylight {
namespace {

std::vector<Vec3> random_points(int count, uint64_t seed) {
    Pcg32 rng(seed);
    std::vector<Vec3> points;
    for (int i = 0; i < count; ++i) points.push_back({rng.next_float(), rng.next_float(), rng.next_float()});
    return points;
}

/// `count` photons of power `power` each at Halton points of the unit square on the floor (y = 0),
/// all arriving from above.
PhotonMap halton_floor_photons(int count, Rgb power) {
    std::vector<Photon> photons;
    for (int i = 0; i < count; ++i)
        photons.push_back({{halton(0, uint64_t(i)), 0, halton(1, uint64_t(i))}, {0, 1, 0}, {0, 1, 0}, power});
    return PhotonMap(std::move(photons), count);
}

TEST(PhotonMap, EmptyMapReturnsNoNeighbours) {
    const PhotonMap map;
    std::vector<Neighbour> out{{1, 1}};
    map.k_nearest({0, 0, 0}, 10, 1, out);
    EXPECT_TRUE(out.empty());
    EXPECT_EQ(map.estimate_irradiance({0, 0, 0}, {0, 0, 1}, {}), Rgb{});
}

TEST(PhotonMap, KNearestMatchesBruteForce) {
    const std::vector<Vec3> points = random_points(5000, 1);
    const PointIndex index(points);
    std::vector<Neighbour> found;
    for (const Vec3& q : random_points(100, 2)) {
        index.k_nearest(q, 20, 0.04f, found);
        std::vector<Neighbour> expected;
        for (uint32_t i = 0; i < points.size(); ++i)
            if (length2(points[i] - q) <= 0.04f) expected.push_back({i, length2(points[i] - q)});
        std::sort(expected.begin(), expected.end(), [](auto a, auto b) { return a.distance2 < b.distance2; });
        expected.resize(std::min<size_t>(expected.size(), 20));
        ASSERT_EQ(found.size(), expected.size());
        for (size_t i = 0; i < found.size(); ++i) EXPECT_EQ(found[i].index, expected[i].index);
    }
}

// Photon maps hold many photons at the same spot (a photon stored twice at one hit, walls
// meeting): equal distances come back in index order, exactly as a brute-force search sorts them.
TEST(PhotonMap, KNearestBreaksTiesByIndexLikeBruteForce) {
    std::vector<Vec3> points = random_points(3000, 3);
    for (int i = 0; i < 3000; i += 3) points[size_t(i)] = points[size_t(i / 2)];  // duplicates
    const PointIndex index(points);
    std::vector<Neighbour> found;
    for (const int k : {1, 7, 300, 5000}) {
        for (const Vec3& q : random_points(30, 4)) {
            index.k_nearest(q, k, 0.09f, found);
            std::vector<Neighbour> expected;
            for (uint32_t i = 0; i < points.size(); ++i)
                if (length2(points[i] - q) <= 0.09f) expected.push_back({i, length2(points[i] - q)});
            std::sort(expected.begin(), expected.end(), [](auto a, auto b) {
                return a.distance2 != b.distance2 ? a.distance2 < b.distance2 : a.index < b.index;
            });
            expected.resize(std::min(expected.size(), size_t(k)));
            ASSERT_EQ(found.size(), expected.size()) << "k " << k;
            for (size_t i = 0; i < found.size(); ++i) ASSERT_EQ(found[i].index, expected[i].index) << "k " << k;
        }
    }
}

// Asked for the farthest first (a sum's fixed order, not sorted), a search finds the same points
// as nearest first, the farthest (ties: the larger index) first when all k were found, and in the
// same order each time it is asked.
TEST(PhotonMap, KNearestFarthestFirstFindsTheSamePoints) {
    std::vector<Vec3> points = random_points(3000, 10);
    for (int i = 0; i < 3000; i += 3) points[size_t(i)] = points[size_t(i / 2)];  // duplicates
    const PointIndex index(points);
    std::vector<Neighbour> sorted, unsorted, again;
    int unsorted_answers = 0;
    for (const int k : {1, 7, 300, 5000}) {
        for (const Vec3& q : random_points(30, 11)) {
            index.k_nearest(q, k, 0.09f, sorted);
            index.k_nearest(q, k, 0.09f, unsorted, PointIndex::Order::farthest_first);
            index.k_nearest(q, k, 0.09f, again, PointIndex::Order::farthest_first);
            ASSERT_EQ(unsorted.size(), sorted.size()) << "k " << k;
            for (size_t i = 0; i < unsorted.size(); ++i)
                ASSERT_TRUE(unsorted[i].index == again[i].index && unsorted[i].distance2 == again[i].distance2);
            if (int(sorted.size()) == k) {
                EXPECT_EQ(unsorted.front().index, sorted.back().index) << "k " << k;
                EXPECT_EQ(unsorted.front().distance2, sorted.back().distance2) << "k " << k;
            }
            unsorted_answers += !std::is_sorted(unsorted.begin(), unsorted.end(), nearer_neighbour);
            std::sort(unsorted.begin(), unsorted.end(), nearer_neighbour);
            for (size_t i = 0; i < unsorted.size(); ++i) ASSERT_EQ(unsorted[i].index, sorted[i].index) << "k " << k;
        }
    }
    EXPECT_GT(unsorted_answers, 30);  // it spared the sort
}

// Told of a point it holds (the last look-up's answer, nearby), the nearest search answers as
// without it: told of the answer itself, of a duplicate level with it (a smaller or larger index)
// or of a farther point; points outside the radius are not told.
TEST(PhotonMap, NearestToldOfAPointAnswersAsWithout) {
    std::vector<Vec3> points = random_points(3000, 6);
    for (int i = 0; i < 3000; i += 3) points[size_t(i)] = points[size_t(i / 2)];  // duplicates
    const PointIndex index(points);
    const float max_distance2 = 0.01f;
    std::vector<Neighbour> expected;
    int told = 0, ties = 0;
    Pcg32 rng(7);
    for (const Vec3& q : random_points(300, 8)) {
        index.k_nearest(q, 1, max_distance2, expected);
        EXPECT_EQ(index.nearest(q, max_distance2).has_value(), !expected.empty());
        // Every duplicate of the answer (level with it, but a larger or smaller index), the answer
        // itself, and random points.
        std::vector<uint32_t> known_points;
        for (uint32_t i = 0; i < points.size() && !expected.empty(); ++i)
            if (points[i] == points[expected[0].index]) known_points.push_back(i);
        for (int i = 0; i < 8; ++i) known_points.push_back(rng.next_u32() % uint32_t(points.size()));
        for (const uint32_t known : known_points) {
            const float distance2 = PointIndex::distance2(points[known], q);
            if (distance2 > max_distance2) continue;
            ++told;
            ties += !expected.empty() && distance2 == expected[0].distance2;
            const std::optional<Neighbour> found = index.nearest(q, max_distance2, Neighbour{known, distance2});
            ASSERT_TRUE(found && !expected.empty());
            EXPECT_EQ(found->index, expected[0].index);
            EXPECT_EQ(found->distance2, expected[0].distance2);
        }
    }
    EXPECT_GT(told, 300);
    EXPECT_GT(ties, 100);
}

// A map composed over another's index (some photons removed, others added in between, the rest
// renumbered) answers exactly as a map built over all its photons, ties included: new photons
// sit exactly on kept and on removed ones.
TEST(PhotonMap, ComposedMapAnswersAsAMapBuiltOverAllItsPhotons) {
    std::vector<Vec3> points = random_points(3000, 5);
    for (int i = 0; i < 3000; i += 3) points[size_t(i)] = points[size_t(i / 2)];  // duplicates
    std::vector<Photon> base_photons;
    for (const Vec3& p : points) base_photons.push_back({p, {0, 0, 1}, {0, 0, 1}, {1, 1, 1}});
    const PhotonMap base(base_photons, 3000);
    std::vector<Photon> photons;
    KeptStaticPhotons kept{std::vector<uint32_t>(points.size(), PointIndex::removed), {}};
    const std::vector<Vec3> extra = random_points(1000, 6);
    for (uint32_t i = 0; i < points.size(); ++i) {
        if (i % 5 != 0) kept.frame_ids[i] = uint32_t(photons.size()), photons.push_back(base_photons[i]);
        if (i % 7 == 0) {
            const Vec3 p = i % 2 ? points[(i * 13) % points.size()] : extra[i / 7];
            kept.added_ids.push_back(uint32_t(photons.size()));
            photons.push_back({p, {0, 0, 1}, {0, 0, 1}, {2, 2, 2}});
        }
    }
    const PhotonMap composed(photons, 3000, base, kept);
    const PhotonMap rebuilt(photons, 3000);
    EXPECT_EQ(composed.indexed_here(), kept.added_ids.size());
    std::vector<Neighbour> a, b;
    for (const int k : {1, 7, 300, 5000})
        for (const Vec3& q : random_points(40, 7)) {
            composed.k_nearest(q, k, 0.3f, a);
            rebuilt.k_nearest(q, k, 0.3f, b);
            ASSERT_EQ(a.size(), b.size()) << "k " << k;
            for (size_t i = 0; i < a.size(); ++i)
                ASSERT_TRUE(a[i].index == b[i].index && a[i].distance2 == b[i].distance2) << "k " << k << ", " << i;
        }
    // From the base's lists of a few more than k: the same answer whenever it gives one, and it
    // gives one unless the removed photons leave the list too short (a fifth are removed here).
    int told = 0, not_told = 0;
    std::vector<uint32_t> base_list;
    for (const int k : {1, 7, 50, 300})
        for (const int margin : {0, 4, 16})
            for (const Vec3& q : random_points(40, 9)) {
                base.k_nearest(q, k + margin, 0.3f, b);
                base_list.clear();
                for (const Neighbour& nb : b) base_list.push_back(nb.index);
                rebuilt.k_nearest(q, k, 0.3f, b);
                if (!composed.k_nearest_from_base(q, k, 0.3f, base, base_list, k + margin, kept.frame_ids, a)) {
                    ++not_told;
                    continue;
                }
                ++told;
                ASSERT_EQ(a.size(), b.size()) << "k " << k << ", margin " << margin;
                for (size_t i = 0; i < a.size(); ++i)
                    ASSERT_TRUE(a[i].index == b[i].index && a[i].distance2 == b[i].distance2)
                        << "k " << k << ", margin " << margin << ", " << i;
            }
    EXPECT_GT(told, 300);
    EXPECT_GT(not_told, 10);
    EXPECT_FALSE(
        rebuilt.k_nearest_from_base(points[0], 7, 0.3f, base, base_list, 7, kept.frame_ids, a));  // not composed
    // Every photon within a radius: the same set (in its own order), and exactly the photons a
    // brute-force scan finds.
    const auto sorted = [](std::vector<Neighbour> found) {
        std::sort(found.begin(), found.end(), [](Neighbour x, Neighbour y) { return x.index < y.index; });
        return found;
    };
    for (const Vec3& q : random_points(40, 8)) {
        composed.within(q, 0.2f, a);
        rebuilt.within(q, 0.2f, b);
        a = sorted(a), b = sorted(b);
        std::vector<Neighbour> expected;
        for (uint32_t i = 0; i < photons.size(); ++i)
            if (length2(photons[i].p - q) <= 0.2f * 0.2f) expected.push_back({i, length2(photons[i].p - q)});
        ASSERT_EQ(a.size(), expected.size());
        ASSERT_EQ(b.size(), expected.size());
        for (size_t i = 0; i < a.size(); ++i)
            ASSERT_TRUE(a[i].index == expected[i].index && b[i].index == expected[i].index &&
                        a[i].distance2 == b[i].distance2);
    }
}

// Photons of total power P spread uniformly over a unit square: irradiance P / 1 m^2, by both
// the plain and the cone-filtered estimate, and only from the side the photons arrived on.
TEST(PhotonMap, UniformPhotonsGiveTheirPowerPerArea) {
    const int count = 40'000;
    const PhotonMap map = halton_floor_photons(count, {2.0f / count, 0, 0});
    const DensitySettings settings{.k = 400, .max_radius = 0.3f};
    EXPECT_NEAR(map.estimate_irradiance({0.5f, 0, 0.5f}, {0, 1, 0}, settings).r, 2.0f, 0.1f);
    EXPECT_NEAR(map.estimate_irradiance_cone({0.5f, 0, 0.5f}, {0, 1, 0}, settings).r, 2.0f, 0.15f);
    EXPECT_EQ(map.estimate_irradiance({0.5f, 0, 0.5f}, {0, -1, 0}, settings).r, 0.0f);
}

// Photons of total power 1 at uniformly random places on a unit square: irradiance 1. The mean
// of many estimates at random points away from the square's edges is 1 within 0.5%; the
// textbook sum of all k photons gives k / (k - 1) = 1.02 at k = 50.
TEST(PhotonMap, DensityEstimateIsUnbiasedForRandomPhotons) {
    const int count = 100'000;
    Pcg32 rng(7);
    std::vector<Photon> photons;
    for (int i = 0; i < count; ++i)
        photons.push_back({{rng.next_float(), 0, rng.next_float()}, {0, 1, 0}, {0, 1, 0}, {1.0f / count, 0, 0}});
    const PhotonMap map(std::move(photons), count);
    double sum = 0;
    const int estimates = 20'000;
    for (int i = 0; i < estimates; ++i) {
        const Vec3 p{0.2f + 0.6f * rng.next_float(), 0, 0.2f + 0.6f * rng.next_float()};
        sum += map.estimate_irradiance(p, {0, 1, 0}, {.k = 50, .max_radius = 0.5f}).r;
    }
    EXPECT_NEAR(sum / estimates, 1.0, 0.005);
}

// The irradiance at a photon is divided by the share of its disc on the surface: half a disc,
// twice the estimate.
TEST(PhotonMap, IrradiancePhotonsDivideByTheSurfacesShareOfTheDisc) {
    const PhotonMap map = halton_floor_photons(1000, {1e-3f, 0, 0});
    const DensitySettings settings{.k = 50, .max_radius = 0.5f};
    const IrradiancePhotons whole(map, 1, settings, {});
    const auto half_disc = [](Vec3, Vec3, float, float, float, uint64_t) { return DiscProbes{.reached = 0x0f0f}; };
    const IrradiancePhotons half(map, 1, settings, {half_disc, [](Vec3, Vec3, float, Vec3) { return true; }});
    const Vec3 p = map.photons()[500].p;
    EXPECT_FLOAT_EQ(half.lookup(p, {0, 1, 0}, 0.1f)->r, 2 * whole.lookup(p, {0, 1, 0}, 0.1f)->r);
}

// Photons the surface does not reach (behind a wall rising from it: the inside of a lamp's
// housing) do not count. Here the probes find half of every disc's cells on the surface (turned
// from estimate to estimate), the photons lie evenly over the floor, and a photon elsewhere is
// not reached: the estimate over that half alone is the whole one's. Counting every photon over
// half the disc doubled it (the light that leaked out of lamp housings).
TEST(PhotonMap, OnlyThePhotonsTheSurfaceReachesCount) {
    const PhotonMap map = halton_floor_photons(20000, {1e-3f, 0, 0});
    const DensitySettings settings{.k = 50, .max_radius = 0.5f};
    const Vec3 up{0, 1, 0};
    const OrthonormalBasis basis = OrthonormalBasis::from_normal(up);
    Pcg32 rng(3);
    double whole = 0, half = 0, leaking = 0;
    for (int i = 0; i < 400; ++i) {
        const Vec3 p{0.2f + 0.6f * rng.next_float(), 0, 0.2f + 0.6f * rng.next_float()};
        const DiscProbes probes{.reached = 0x0f0f, .turn = rng.next_float()};
        const auto half_disc = [&](Vec3, Vec3, float, float, float, uint64_t) { return probes; };
        const SurfaceCoverage one_half{half_disc, [&](Vec3 c, Vec3, float radius, Vec3 q) {
                                           const Vec3 local = basis.to_local(q - c);
                                           return probes.reached_cell(local.x, local.y, radius * radius);
                                       }};
        const SurfaceCoverage every_photon{half_disc, [](Vec3, Vec3, float, Vec3) { return true; }};
        whole += map.estimate_irradiance(p, up, settings).r;
        half += map.estimate_irradiance_on_surface(p, up, settings, one_half, uint64_t(i)).r;
        leaking += map.estimate_irradiance_on_surface(p, up, settings, every_photon, uint64_t(i)).r;
    }
    EXPECT_NEAR(half / whole, 1.0, 0.03);
    EXPECT_NEAR(leaking / whole, 2.0, 1e-4);
}

// A disc's cells as its probes lay them out: the inner ring within the half-area radius, sectors
// centred on the probes' angles, the outer ring turned by half a sector more.
TEST(PhotonMap, DiscProbeCellsFollowTheProbesLayout) {
    const DiscProbes only_first_inner{.reached = 0x0001, .turn = 0.25f};
    const float r2 = 1;
    const auto at = [](float radius, float sectors) {
        const float angle = 2 * pi * sectors / DiscProbes::sectors;
        return std::pair{radius * std::cos(angle), radius * std::sin(angle)};
    };
    for (const float offset : {-0.45f, 0.0f, 0.45f}) {
        const auto [x, y] = at(0.5f, 0.25f + offset);
        EXPECT_TRUE(only_first_inner.reached_cell(x, y, r2)) << offset;
    }
    const auto [x1, y1] = at(0.5f, 0.25f + 0.55f);  // the next sector
    EXPECT_FALSE(only_first_inner.reached_cell(x1, y1, r2));
    const auto [x2, y2] = at(0.9f, 0.25f);  // the outer ring
    EXPECT_FALSE(only_first_inner.reached_cell(x2, y2, r2));
    const DiscProbes only_first_outer{.reached = 0x0100, .turn = 0.25f};
    const auto [x3, y3] = at(0.9f, 0.75f);  // its probe's angle: half a sector on
    EXPECT_TRUE(only_first_outer.reached_cell(x3, y3, r2));
    EXPECT_FLOAT_EQ(DiscProbes{.reached = 0x0f0f}.share(), 0.5f);
}

TEST(PhotonMap, IrradiancePhotonLookupRespectsNormals) {
    const PhotonMap map = halton_floor_photons(1000, {1e-3f, 1e-3f, 1e-3f});
    const IrradiancePhotons irradiance(map, 2, {.k = 50, .max_radius = 0.5f}, {});
    // One in two, chosen by the photons' hash: about half.
    EXPECT_NEAR(double(irradiance.size()), 500.0, 50.0);
    EXPECT_TRUE(irradiance.lookup({0.5f, 0, 0.5f}, {0, 1, 0}, 0.2f).has_value());
    EXPECT_FALSE(irradiance.lookup({0.5f, 0, 0.5f}, {0, -1, 0}, 0.2f).has_value());
    EXPECT_FALSE(irradiance.lookup({5, 0, 5}, {0, 1, 0}, 0.2f).has_value());
}

// The irradiance at photons is computed on first use: a look-up returns the estimate at the
// nearest precomputed photon, and only the photons looked up are ever computed.
TEST(PhotonMap, IrradiancePhotonsComputeOnlyWhatIsLookedUp) {
    const PhotonMap map = halton_floor_photons(1000, {1e-3f, 0, 0});
    const DensitySettings settings{.k = 50, .max_radius = 0.5f};
    const IrradiancePhotons irradiance(map, 1, settings, {});
    EXPECT_EQ(irradiance.computed(), 0);
    const Photon& photon = map.photons()[123];
    const std::optional<Rgb> E = irradiance.lookup(photon.p, {0, 1, 0}, 0.2f);
    ASSERT_TRUE(E.has_value());
    EXPECT_EQ(*E, map.estimate_irradiance(photon.p, photon.n, settings));
    EXPECT_EQ(irradiance.lookup(photon.p, {0, 1, 0}, 0.2f), E);
    EXPECT_EQ(irradiance.computed(), 1);
    irradiance.compute_all();
    EXPECT_EQ(irradiance.computed(), 1000);
    EXPECT_EQ(irradiance.lookup(photon.p, {0, 1, 0}, 0.2f), E);
}

TEST(Halton, ComponentsAreInUnitIntervalAndEquidistributed) {
    for (const int d : {0, 1, 7, 63, 127}) {
        double sum = 0;
        for (uint64_t i = 0; i < 10'000; ++i) {
            const float v = halton(d, i);
            ASSERT_GE(v, 0.0f);
            ASSERT_LT(v, 1.0f);
            sum += v;
        }
        EXPECT_NEAR(sum / 10'000, 0.5, 0.01) << "dimension " << d;
    }
}

}  // namespace
}  // namespace steadylight
