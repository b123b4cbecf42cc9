// PointIndex::updated: an index whose set of points changed a little answers as one built over
// the new set, whichever way it keeps the change (skipped points, points filed in leaves, ranges
// built again).
#include "steadylight/photons/point_index.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "steadylight/base/rng.h"

namespace steadylight {
namespace {

/// A point of the unit cube, on a grid of 1/32 half the time: many points share coordinates
/// with each other and with the tree's splitting planes.
Vec3 grid_or_random_point(Pcg32& rng) {
    Vec3 p{rng.next_float(), rng.next_float(), rng.next_float()};
    if (rng.next_float() < 0.5f) p = {std::floor(p.x * 32) / 32, std::floor(p.y * 32) / 32, std::floor(p.z * 32) / 32};
    return p;
}

/// A set of points and what became of it: some removed, others added with new ids.
struct ChangedSet {
    std::vector<Vec3> before;
    std::vector<uint32_t> ids_by_id;  // per point of `before`: its new id, or PointIndex::removed
    std::vector<Vec3> added;
    std::vector<uint32_t> added_ids;

    /// Every point of the new set with its new id.
    std::vector<std::pair<Vec3, uint32_t>> after() const {
        std::vector<std::pair<Vec3, uint32_t>> points;
        for (size_t i = 0; i < before.size(); ++i)
            if (ids_by_id[i] != PointIndex::removed) points.push_back({before[i], ids_by_id[i]});
        for (size_t i = 0; i < added.size(); ++i) points.push_back({added[i], added_ids[i]});
        return points;
    }
};

/// 6,000 points of which 3% are removed at random and every one in a corner box (most of a
/// range there), and 200 added at random, 1,500 in a small ball where there were none (one
/// leaf's cell) and 40 on top of points removed; new ids shuffled, as a renumbered set's are.
ChangedSet changed_set() {
    Pcg32 rng(7);
    ChangedSet set;
    for (int i = 0; i < 6000; ++i) set.before.push_back(grid_or_random_point(rng));
    const Vec3 ball{0.5f, 0.5f, 0.5f};
    for (Vec3& p : set.before)
        if (length(p - ball) < 0.1f) p = p + normalize(p - ball) * 0.1f;  // an empty ball
    const auto in_corner = [](Vec3 p) { return p.x < 0.2f && p.y < 0.2f && p.z < 0.3f; };
    std::vector<uint32_t> removed;
    for (uint32_t i = 0; i < set.before.size(); ++i)
        if (in_corner(set.before[i]) || rng.next_float() < 0.03f) removed.push_back(i);
    for (int i = 0; i < 200; ++i) set.added.push_back(grid_or_random_point(rng));
    for (int i = 0; i < 1500; ++i) {
        const Vec3 d{rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f};
        set.added.push_back(ball + d * 0.1f);
    }
    for (int i = 0; i < 40; ++i) set.added.push_back(set.before[removed[size_t(i) * 7 % removed.size()]]);
    // New ids: a shuffle of 0 .. kept + added - 1.
    const size_t count = set.before.size() - removed.size() + set.added.size();
    std::vector<uint32_t> ids(count);
    for (uint32_t i = 0; i < count; ++i) ids[i] = i;
    for (size_t i = count - 1; i > 0; --i) std::swap(ids[i], ids[rng.next_u32() % (i + 1)]);
    set.ids_by_id.assign(set.before.size(), PointIndex::removed);
    size_t next = 0;
    for (uint32_t i = 0, r = 0; i < set.before.size(); ++i)
        if (r < removed.size() && removed[r] == i)
            ++r;
        else
            set.ids_by_id[i] = ids[next++];
    for (size_t i = 0; i < set.added.size(); ++i) set.added_ids.push_back(ids[next++]);
    return set;
}

/// The up to k nearest of `points` to q within sqrt(max_distance2), by distance then id.
std::vector<Neighbour> brute_force(const std::vector<std::pair<Vec3, uint32_t>>& points, Vec3 q, int k,
                                   float max_distance2) {
    std::vector<Neighbour> found;
    for (const auto& [p, id] : points)
        if (const float d2 = PointIndex::distance2(p, q); d2 <= max_distance2) found.push_back({id, d2});
    std::sort(found.begin(), found.end(), nearer_neighbour);
    found.resize(std::min(found.size(), size_t(k)));
    return found;
}

void expect_same(const std::vector<Neighbour>& found, const std::vector<Neighbour>& expected, const char* what) {
    ASSERT_EQ(found.size(), expected.size()) << what;
    for (size_t i = 0; i < found.size(); ++i) {
        ASSERT_EQ(found[i].index, expected[i].index) << what << " #" << i;
        ASSERT_EQ(found[i].distance2, expected[i].distance2) << what << " #" << i;
    }
}

// Queries everywhere, and near the changes in particular (the empty ball filled, the corner
// emptied), for k = 1 (with and without a known point), 8 and 64, and every point within a radius.
TEST(PointIndex, UpdatedAnswersAsAnIndexOverTheNewSet) {
    const ChangedSet set = changed_set();
    const PointIndex updated = PointIndex(set.before).updated(set.ids_by_id, set.added, set.added_ids);
    const std::vector<std::pair<Vec3, uint32_t>> after = set.after();
    EXPECT_EQ(updated.size(), set.before.size() + set.added.size());
    Pcg32 rng(8);
    std::vector<Vec3> queries;
    for (int i = 0; i < 300; ++i) queries.push_back(grid_or_random_point(rng));
    for (int i = 0; i < 100; ++i)
        queries.push_back({rng.next_float() * 0.25f, rng.next_float() * 0.25f, rng.next_float() * 0.35f});
    for (int i = 0; i < 100; ++i)
        queries.push_back(Vec3{0.5f, 0.5f, 0.5f} +
                          Vec3{rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f} * 0.3f);
    std::vector<Neighbour> found;
    std::optional<Vec3> last;  // the previous query's nearest point, told to the next search
    for (const Vec3& q : queries) {
        for (const int k : {1, 8, 64}) {
            updated.k_nearest(q, k, 0.04f, found);
            expect_same(found, brute_force(after, q, k, 0.04f), "k_nearest");
        }
        const std::vector<Neighbour> nearest = brute_force(after, q, 1, 0.04f);
        std::optional<Neighbour> known;
        if (last && PointIndex::distance2(*last, q) <= 0.04f) {
            const auto at_last =
                std::find_if(after.begin(), after.end(), [&](const auto& p) { return p.first == *last; });
            known = Neighbour{at_last->second, PointIndex::distance2(*last, q)};
        }
        const std::optional<Neighbour> one = updated.nearest(q, 0.04f, known);
        expect_same(one ? std::vector<Neighbour>{*one} : std::vector<Neighbour>{}, nearest, "nearest");
        if (one)
            last =
                std::find_if(after.begin(), after.end(), [&](const auto& p) { return p.second == one->index; })->first;
        updated.within(q, 0.01f, found);
        std::sort(found.begin(), found.end(), nearer_neighbour);
        expect_same(found, brute_force(after, q, int(after.size()), 0.01f), "within");
    }
}

// With nothing added the removed points are only skipped; with nothing kept, the added ones
// are the index.
TEST(PointIndex, UpdatedWithOnlyRemovalsOrOnlyAdditions) {
    const ChangedSet set = changed_set();
    ChangedSet removals_only = set;
    removals_only.added.clear(), removals_only.added_ids.clear();
    ChangedSet all_new = set;
    all_new.before.clear(), all_new.ids_by_id.clear();
    Pcg32 rng(9);
    std::vector<Neighbour> found;
    for (const ChangedSet* changed : {&removals_only, &all_new}) {
        const PointIndex updated =
            PointIndex(changed->before).updated(changed->ids_by_id, changed->added, changed->added_ids);
        for (int i = 0; i < 100; ++i) {
            const Vec3 q = grid_or_random_point(rng);
            updated.k_nearest(q, 16, 0.04f, found);
            expect_same(found, brute_force(changed->after(), q, 16, 0.04f), "k_nearest");
        }
    }
}

}  // namespace
}  // namespace steadylight
