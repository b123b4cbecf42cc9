#include "steadylight/photons/surface_coverage.h"

#include <gtest/gtest.h>

#include "support/scene_builder.h"

namespace steadylight {
namespace {

using testing::add_material;
using testing::add_object;
using testing::make_empty_scene;

/// A 4 m floor (y = 0, x and z in [0, 4]) with a wall standing on its x = 0 edge, a 1 m cube on
/// it centred at (2, 0.5, 2) and a ball of radius 0.5 floating at (3, 2, 3).
SceneDesc floor_wall_cube_ball() {
    SceneDesc desc = make_empty_scene({2, 2, -5}, {2, 0, 2});
    const int white = add_material(desc, {});
    add_object(desc, make_quad({0, 0, 0}, {0, 0, 4}, {4, 0, 0}), white);
    add_object(desc, make_quad({0, 0, 0}, {0, 3, 0}, {0, 0, 4}), white);
    add_object(desc, make_box({2, 0.5f, 2}, {1, 1, 1}), white);
    add_object(desc, Sphere{{3, 2, 3}, 0.5f}, white);
    return desc;
}

/// The coverage of the disc of radius 0.2 at p, averaged over 64 seeds (each alone is a
/// sixteenth-quantised sample).
double mean_coverage(const SurfaceCoverage& coverage, Vec3 p, Vec3 n) {
    double sum = 0;
    for (uint64_t seed = 0; seed < 64; ++seed)
        sum += coverage.probes(p, n, 0.2f, 0.2f * coverage_lift, 0.2f, seed).share();
    return sum / 64;
}

// Where a disc lies wholly on the surface, flat or curving away (the ball), all of it counts;
// on an edge, concave (floor meeting the wall) or convex (the cube's rim, the floor's open
// edge), half; at a corner with two open edges, a quarter; across a step it does not climb
// (the floor at the foot of the cube) the part behind the step is left out.
TEST(SurfaceCoverage, CountsTheShareOfTheDiscOnTheSurface) {
    const Scene scene(floor_wall_cube_ball());
    const PreparedFrame prepared(scene, 0);
    const SurfaceCoverage coverage = surface_coverage(prepared.context(), Visibility::everything);
    const Vec3 up{0, 1, 0};
    EXPECT_EQ(coverage.probes({1, 0, 1}, up, 0.2f, 0.2f * coverage_lift, 0.2f, 0).share(), 1.0f);
    EXPECT_NEAR(mean_coverage(coverage, {3, 2.5f, 3}, up), 1.0, 1e-6);          // the ball's top
    EXPECT_NEAR(mean_coverage(coverage, {1e-3f, 0, 1}, up), 0.5, 0.03);         // floor at the wall
    EXPECT_NEAR(mean_coverage(coverage, {0, 1e-3f, 1}, {1, 0, 0}), 0.5, 0.03);  // wall at the floor
    EXPECT_NEAR(mean_coverage(coverage, {2.499f, 1, 2}, up), 0.5, 0.03);        // the cube's rim
    EXPECT_NEAR(mean_coverage(coverage, {1, 0, 1e-3f}, up), 0.5, 0.03);         // the floor's open edge
    EXPECT_NEAR(mean_coverage(coverage, {3.999f, 0, 3.999f}, up), 0.25, 0.03);  // open corner
    EXPECT_NEAR(mean_coverage(coverage, {1.499f, 0, 2}, up), 0.5, 0.03);        // at the cube's foot
}

// Whether a photon lies on the surface an estimate is for: the floor reaches its own points, but
// not the floor under the cube behind the cube's side, nor the cube's top, in front of the
// floor's plane (a lamp housing's top hung just under a ceiling is the same case).
TEST(SurfaceCoverage, ReachesOnlyPointsOfItsOwnSurface) {
    const Scene scene(floor_wall_cube_ball());
    const PreparedFrame prepared(scene, 0);
    const SurfaceCoverage coverage = surface_coverage(prepared.context(), Visibility::everything);
    const Vec3 up{0, 1, 0};
    EXPECT_TRUE(coverage.reaches({1, 0, 1}, up, 0.2f, {1.1f, 0, 1.05f}));
    EXPECT_TRUE(coverage.reaches({1.4f, 0, 2}, up, 0.5f, {1.1f, 0, 2}));
    EXPECT_FALSE(coverage.reaches({1.4f, 0, 2}, up, 0.5f, {1.7f, 0, 2}));  // under the cube
    EXPECT_FALSE(coverage.reaches({1.4f, 0, 2}, up, 2.0f, {2, 1, 2}));     // the cube's top
}

// Light passes through glass, and photons land on the floor under and behind a glass block:
// the probes look through it (rough glass too), where an opaque block hides the floor.
TEST(SurfaceCoverage, LooksThroughGlass) {
    for (const float roughness : {0.0f, 0.3f}) {
        SceneDesc desc = make_empty_scene({2, 2, -5}, {2, 0, 2});
        add_object(desc, make_quad({0, 0, 0}, {0, 0, 4}, {4, 0, 0}), add_material(desc, {}));
        add_object(desc, make_box({2, 0.5f, 2}, {1, 1, 1}),
                   add_material(desc, {.type = MaterialType::dielectric, .roughness = roughness}));
        const Scene scene(std::move(desc));
        const PreparedFrame prepared(scene, 0);
        const SurfaceCoverage coverage = surface_coverage(prepared.context(), Visibility::everything);
        const Vec3 up{0, 1, 0};
        EXPECT_NEAR(mean_coverage(coverage, {1.499f, 0, 2}, up), 1.0, 1e-6) << roughness;  // at the block's foot
        EXPECT_NEAR(mean_coverage(coverage, {2, 0, 2}, up), 1.0, 1e-6) << roughness;       // under it
        EXPECT_TRUE(coverage.reaches({1.4f, 0, 2}, up, 0.5f, {1.7f, 0, 2})) << roughness;
        EXPECT_TRUE(coverage.reaches({2, 0, 2}, up, 0.5f, {1.6f, 0, 2.1f})) << roughness;
    }
}

}  // namespace
}  // namespace steadylight
