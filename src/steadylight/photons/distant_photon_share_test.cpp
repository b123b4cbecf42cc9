// distant_photons_inside: in a closed room lit by the world through one window, with the camera
// inside, nearly every photon aimed through the window as a portal reaches a side the camera
// sees, and few of those from the disc covering the whole scene do (most strike the walls'
// outer faces).
#include "steadylight/photons/distant_photon_share.h"

#include <gtest/gtest.h>

#include "support/scene_builder.h"

namespace steadylight {
namespace {

/// The room [-1, 1]^3 with a window in its +x wall (y in [-0.2, 0.2], z in [-0.4, 0.4]) and the
/// camera inside looking at the -x wall, under a uniform world; the window as a portal when asked.
SceneDesc room_with_window(bool portal) {
    SceneDesc desc = testing::make_empty_scene({0.9f, 0, 0}, {-1, 0, 0}, 32, 24, 100);
    const int white = testing::add_material(desc, MaterialDesc{});
    const auto wall = [&](Vec3 corner, Vec3 u, Vec3 v) { testing::add_object(desc, make_quad(corner, u, v), white); };
    wall({-1, -1, -1}, {2, 0, 0}, {0, 0, 2});  // floor
    wall({-1, 1, -1}, {0, 0, 2}, {2, 0, 0});   // ceiling
    wall({-1, -1, -1}, {0, 2, 0}, {2, 0, 0});  // z = -1
    wall({-1, -1, 1}, {2, 0, 0}, {0, 2, 0});   // z = 1
    wall({-1, -1, -1}, {0, 0, 2}, {0, 2, 0});  // x = -1
    // x = 1 around the window
    wall({1, -1, -1}, {0, 0, 2}, {0, 0.8f, 0});
    wall({1, 0.2f, -1}, {0, 0, 2}, {0, 0.8f, 0});
    wall({1, -0.2f, -1}, {0, 0, 0.6f}, {0, 0.4f, 0});
    wall({1, -0.2f, 0.4f}, {0, 0, 0.6f}, {0, 0.4f, 0});
    desc.world = WorldDesc::uniform({1, 1, 1});
    if (portal) desc.portals = {{.corner = {1, -0.2f, -0.4f}, .edge_u = {0, 0, 0.8f}, .edge_v = {0, 0.4f, 0}}};
    return desc;
}

TEST(DistantPhotonShare, PhotonsAimedThroughAPortalReachWhatTheCameraSees) {
    for (const bool portal : {false, true}) {
        const Scene scene(room_with_window(portal));
        ASSERT_EQ(portal, !scene.desc().portals.empty() && scene.desc().portals[0].inward_normal().x < -0.99f);
        const PreparedFrame prepared(scene, 0);
        const CameraSeenSides seen(scene, prepared.context().tracer);
        const std::optional<double> share = distant_photons_inside(prepared.context(), seen, 8192);
        ASSERT_TRUE(share);
        if (portal)
            EXPECT_GT(*share, 0.7);  // the map's half of the directions: half of them enter
        else
            EXPECT_LT(*share, 0.05);  // the window is 0.32 of the 24 square units of outer walls
    }
}

TEST(DistantPhotonShare, NoLightFromFarAwayHasNoShare) {
    SceneDesc desc = room_with_window(false);
    desc.world.reset();
    desc.objects[0].emission = {1, 1, 1};
    const Scene scene(desc);
    const PreparedFrame prepared(scene, 0);
    EXPECT_FALSE(distant_photons_inside(prepared.context(), CameraSeenSides(scene, prepared.context().tracer)));
}

}  // namespace
}  // namespace steadylight
