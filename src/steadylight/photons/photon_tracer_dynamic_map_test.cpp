// The dynamic photon map of photon tracing (photon_tracer.h), traced and composed from the static
// paths (photon_paths.h): each of its rules (paper §3.1, Figure 2), checked on small scenes.
#include <gtest/gtest.h>

#include "steadylight/photons/photon_paths.h"
#include "steadylight/photons/photon_tracer.h"
#include "support/scene_builder.h"

namespace steadylight {
namespace {

using testing::add_material;
using testing::add_object;
using testing::make_empty_scene;

constexpr PhotonSettings settings{.global_photons = 40'000, .caustic_photons = 0};

/// A closed white box [-2,2] x [0,4] x [-2,2] lit by a small downward quad light under its
/// ceiling; `dynamic` spheres (centre, radius) are added as dynamic objects.
SceneDesc box_desc(const std::vector<std::pair<Vec3, float>>& dynamic) {
    SceneDesc desc = make_empty_scene({0, 2, -1.9f}, {0, 2, 0});
    const int white = add_material(desc, {.reflectance = {0.7f, 0.7f, 0.7f}});
    add_object(desc, make_box({0, 2, 0}, {4, 4, 4}), white);  // seen from inside: two-sided Lambert
    add_object(desc, make_quad({-0.25f, 3.95f, -0.25f}, {0.5f, 0, 0}, {0, 0, 0.5f}), white, {50, 50, 50});
    for (const auto& [center, radius] : dynamic) {
        add_object(desc, Sphere{center, radius}, white);
        desc.objects.back().marked_dynamic = true;
    }
    return desc;
}

Scene box_scene(const std::vector<std::pair<Vec3, float>>& dynamic) { return Scene(box_desc(dynamic)); }

struct Maps {
    TracedPhotons complete;
    PhotonMap static_global;
};

Maps trace_both(const Scene& scene) {
    const PreparedFrame frame(scene, 0);
    return {trace_photons(frame.context(), settings, Visibility::everything),
            trace_photons(frame.context(), settings, Visibility::static_only).global};
}

/// Total power of the indirect photons (bounce > 0) of a map.
Rgb indirect_power(const PhotonMap& map) {
    Rgb sum;
    for (const Photon& photon : map.photons())
        if (photon.bounce > 0) sum += photon.power;
    return sum;
}

bool on_sphere(Vec3 p, Vec3 center, float radius) { return std::abs(length(p - center) - radius) < 1e-3f; }

/// Static map + dynamic map = complete map, photon for photon: each path is the same in both
/// scenes up to its first dynamic hit, the negative photons are exactly the static path's later
/// photons, and the positive ones exactly the complete path's.
void expect_energy_balance(const Maps& maps) {
    const Rgb lhs = indirect_power(maps.static_global) + indirect_power(maps.complete.dynamic);
    const Rgb rhs = indirect_power(maps.complete.global);
    EXPECT_NEAR(lhs.g, rhs.g, 1e-4f * rhs.g);
    EXPECT_GT(maps.complete.dynamic.size(), 0u);
}

TEST(DynamicPhotons, ObjectOutsideEveryLightPathLeavesTheDynamicMapEmpty) {
    const Maps maps = trace_both(box_scene({{{10, 2, 0}, 0.5f}}));  // outside the closed box
    EXPECT_EQ(maps.complete.dynamic.size(), 0u);
    EXPECT_EQ(maps.complete.global.size(), maps.static_global.size());
}

// Caustic photons (every bounce before specular) stay out of the dynamic map: their change is
// in the frame's caustic map already, and L_t counting it again made mirror_room's localized
// frames 1% dark (the walls its glossy floor lights, up to 14%). In a black box a moving mirror
// ball changes nothing but caustics and direct hits.
TEST(DynamicPhotons, CausticPhotonsStayOutOfTheDynamicMap) {
    SceneDesc desc = box_desc({});
    desc.materials[0].reflectance = {0, 0, 0};
    add_object(desc, Sphere{{0, 2, 0}, 0.6f},
               add_material(desc, {.type = MaterialType::mirror, .reflectance = {1, 1, 1}}));
    desc.objects.back().marked_dynamic = true;
    const Maps maps = trace_both(Scene(desc));
    long caustic = 0;
    for (const Photon& photon : maps.complete.global.photons()) caustic += photon.bounce == 1;
    EXPECT_GT(caustic, 1000);  // the ball throws them on the walls
    EXPECT_EQ(maps.complete.dynamic.size(), 0u);
}

// Rule: a direct hit on a dynamic object (Fig. 2, point a) and the static surface its negative
// photon reaches first (point b) are not stored; later hits are.
TEST(DynamicPhotons, DirectHitsAreNotStoredInTheDynamicMap) {
    const Maps maps = trace_both(box_scene({{{0, 2.5f, 0}, 0.6f}}));
    int negative = 0, positive = 0;
    for (const Photon& photon : maps.complete.dynamic.photons()) {
        EXPECT_GT(photon.bounce, 0);
        (photon.power.g < 0 ? negative : positive) += 1;
    }
    EXPECT_GT(negative, 100);
    EXPECT_GT(positive, 100);
    expect_energy_balance(maps);
}

// Rule: negative photons ignore dynamic objects (Fig. 2, h to i), so none lands on one.
TEST(DynamicPhotons, NegativePhotonsPassThroughDynamicObjects) {
    const Vec3 upper{0, 3, 0}, lower{0, 1.2f, 0};
    const Maps maps = trace_both(box_scene({{upper, 0.5f}, {lower, 0.6f}}));
    for (const Photon& photon : maps.complete.dynamic.photons())
        if (photon.power.g < 0) {
            EXPECT_FALSE(on_sphere(photon.p, upper, 0.5f) || on_sphere(photon.p, lower, 0.6f)) << to_string(photon.p);
        }
    expect_energy_balance(maps);
}

// Rule: a path that meets a second dynamic object spawns no second negative photon (Fig. 2,
// point e): the energy only moves on. A second one would break the balance.
TEST(DynamicPhotons, SecondDynamicHitSpawnsNoNegativePhoton) {
    const Maps maps = trace_both(box_scene({{{-0.6f, 1, 0}, 0.5f}, {{0.6f, 1, 0}, 0.5f}}));
    expect_energy_balance(maps);
}

/// The maps composed from `scene`'s static paths at frame 0 against the maps traced whole.
void expect_composed_maps_equal_traced(const Scene& scene) {
    const PreparedFrame frame(scene, 0);
    const ComposedPhotons composed =
        compose_photons(frame.context(), trace_static_photon_paths(frame.context(), settings));
    const TracedPhotons traced = trace_photons(frame.context(), settings);
    EXPECT_TRUE(same_photons(composed.maps.global, traced.global));
    EXPECT_TRUE(same_photons(composed.maps.dynamic, traced.dynamic));
    EXPECT_EQ(composed.maps.dynamic.size(), traced.dynamic.size());
    EXPECT_GT(composed.retraced_paths, 0);
}

// The balance, the other way round: the static paths, with the paths that meet a dynamic object
// retraced from there (negative photons taken from the static path itself), give the complete
// and dynamic maps photon for photon (photon_paths.h).
TEST(DynamicPhotons, StaticPathsRetracedWhereTheyMeetDynamicObjectsGiveTheSameMaps) {
    for (const auto& spheres :
         std::vector<std::vector<std::pair<Vec3, float>>>{{{{0, 2.5f, 0}, 0.6f}},
                                                          {{{0, 3, 0}, 0.5f}, {{0, 1.2f, 0}, 0.6f}},
                                                          {{{-0.6f, 1, 0}, 0.5f}, {{0.6f, 1, 0}, 0.5f}}})
        expect_composed_maps_equal_traced(box_scene(spheres));
}

// The same with a dynamic ball inside absorbing glass (a stone in tinted water): a path resumes
// from a ray inside the glass that the ball now cuts short, and loses to absorption only what
// the shorter ray crosses, as in full tracing, since a kept ray holds the power it starts with.
TEST(DynamicPhotons, StaticPathsRetracedInsideAbsorbingGlassGiveTheSameMaps) {
    SceneDesc desc = box_desc({{{0.2f, 1.6f, 0}, 0.4f}});
    MaterialDesc glass{.type = MaterialType::dielectric, .ior = 1, .roughness = 0};
    glass.attenuation_color = {0.8f, 0.5f, 0.2f};
    glass.attenuation_distance = 0.5f;
    add_object(desc, Sphere{{0, 1.6f, 0}, 1.2f}, add_material(desc, glass));
    expect_composed_maps_equal_traced(Scene(std::move(desc)));
}

TEST(DynamicPhotons, StaticPassSeesNoDynamicObject) {
    const Vec3 center{0, 2.5f, 0};
    const Maps maps = trace_both(box_scene({{center, 0.6f}}));
    for (const Photon& photon : maps.static_global.photons()) EXPECT_FALSE(on_sphere(photon.p, center, 0.6f));
    EXPECT_EQ(trace_photons(PreparedFrame(box_scene({{center, 0.6f}}), 0).context(), settings, Visibility::static_only)
                  .dynamic.size(),
              0u);
}

}  // namespace
}  // namespace steadylight
