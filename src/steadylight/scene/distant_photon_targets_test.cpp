// Photons aimed at targets carry the same light as photons spread over the whole disc: through
// any region, the sum of 1 / pdf over the photons that cross it estimates its area across the
// light, whether the region is a target or not; only the number of photons there changes.
#include "steadylight/scene/distant_photon_targets.h"

#include <gtest/gtest.h>

#include "steadylight/base/rng.h"
#include "steadylight/base/sampling.h"

namespace steadylight {
namespace {

const BoundingSphere scene{{0, 1, 0}, 2};
const Vec3 travel = normalize(Vec3{-1, -1, 0.2f});

/// Whether a photon starting at `p` along `travel` passes within `radius` of `centre`.
bool crosses(Vec3 p, Vec3 centre, float radius) {
    const Vec3 to_centre = centre - p;
    return length(to_centre - travel * dot(to_centre, travel)) <= radius;
}

/// Σ 1/pdf over `n` photons that cross the disc of `radius` about `centre` facing the light,
/// over n (its area across the light, π radius², in expectation), and how many crossed.
std::pair<double, int> crossing_area(const DistantPhotonTargets& targets, Vec3 centre, float radius, int n) {
    Pcg32 rng(3);
    double sum = 0;
    int count = 0;
    for (int i = 0; i < n; ++i) {
        const DistantPhotonTargets::Start start = targets.sample_start(travel, rng.next_vec2());
        if (!crosses(start.p, centre, radius)) continue;
        EXPECT_GT(start.pdf, 0);
        sum += 1 / start.pdf;
        ++count;
    }
    return {sum / n, count};
}

TEST(DistantPhotonTargets, AimedPhotonsCarryTheSameLightWhereverTheyGo) {
    // Light comes in by a window about (1, 1, 0): crossings of photons travelling `travel` there.
    std::vector<std::pair<Vec3, Vec3>> crossings;
    Pcg32 rng(1);
    for (int i = 0; i < 400; ++i)
        crossings.emplace_back(travel, Vec3{1, 0.6f + 0.8f * rng.next_float(), -0.4f + 0.8f * rng.next_float()});
    const DistantPhotonTargets aimed(scene, crossings), spread(scene, {});
    EXPECT_GT(aimed.marked_cells(), 0u);
    EXPECT_EQ(spread.marked_cells(), 0u);
    const float radius = 0.3f;
    const double area = pi * radius * radius;
    for (const Vec3 centre : {Vec3{1, 1, 0}, Vec3{-1, 1.5f, 0.5f}}) {
        const auto [aimed_area, aimed_count] = crossing_area(aimed, centre, radius, 400000);
        const auto [spread_area, spread_count] = crossing_area(spread, centre, radius, 400000);
        EXPECT_NEAR(aimed_area, area, 0.03 * area) << centre.x;
        EXPECT_NEAR(spread_area, area, 0.03 * area) << centre.x;
        // The window gets many times the photons; elsewhere fewer, never none.
        if (centre.x > 0)
            EXPECT_GT(aimed_count, 5 * spread_count);
        else
            EXPECT_GT(aimed_count, 0);
    }
}

// Directions aimed at the marked bins: each sample's pdf is the density pdf() gives, and the
// density integrates to one: Σ 1/pdf over samples estimates the solid angle of the bins it
// covers, which uniform directions on the sphere measure too. Bins without light get nothing.
TEST(DistantPhotonTargets, AimedDirectionsHaveTheDensityTheySay) {
    std::vector<std::pair<Vec3, Vec3>> crossings;
    Pcg32 marks(2);
    for (int i = 0; i < 4000; ++i) {
        // Out up a diagonal (the octahedral map's bins are smallest there by solid angle), and down.
        const Vec3 out = i % 2 ? normalize(Vec3{1, 0.8f + 0.6f * marks.next_float(), 0.4f + 0.6f * marks.next_float()})
                               : normalize(Vec3{0.3f * marks.next_float(), 0.3f * marks.next_float(), -1});
        crossings.emplace_back(-out, Vec3{1.5f, 0.5f, 0});
    }
    const DistantPhotonTargets targets(scene, crossings);
    EXPECT_FALSE(DistantPhotonTargets(scene, {}).aimed_directions([](Vec3) { return 1.0f; }));
    EXPECT_FALSE(targets.aimed_directions([](Vec3) { return 0.0f; }));
    for (const bool dark_below : {false, true}) {
        // Photons travelling up come from below.
        const std::optional<AimedDirections> aimed =
            targets.aimed_directions([&](Vec3 d) { return dark_below && d.z > 0 ? 0.0f : 1.0f; });
        ASSERT_TRUE(aimed);
        Pcg32 rng(5);
        const int n = 400000;
        double covered = 0, measured = 0;
        int up = 0;
        for (int i = 0; i < n; ++i) {
            const AimedDirections::Sample s = aimed->sample(rng.next_vec2());
            ASSERT_GT(s.pdf, 0);
            EXPECT_NEAR(aimed->pdf(s.d), s.pdf, 1e-4f * s.pdf);
            covered += 1 / s.pdf / n;
            up += s.d.z > 0;
            measured += aimed->pdf(sample_uniform_sphere(rng.next_vec2())) > 0 ? 4 * pi / n : 0;
        }
        EXPECT_NEAR(covered, measured, 0.02 * measured) << dark_below;
        if (dark_below)
            EXPECT_EQ(up, 0);
        else
            EXPECT_GT(up, n / 10);
    }
}

TEST(DistantPhotonTargets, TheSameCrossingsGiveTheSameTargets) {
    const std::vector<std::pair<Vec3, Vec3>> crossings = {{travel, {1, 1, 0}}, {normalize(Vec3{0, -1, 0}), {0, 0, 0}}};
    EXPECT_EQ(DistantPhotonTargets(scene, crossings).hash(), DistantPhotonTargets(scene, crossings).hash());
    EXPECT_NE(DistantPhotonTargets(scene, crossings).hash(), DistantPhotonTargets(scene, {}).hash());
}

}  // namespace
}  // namespace steadylight
