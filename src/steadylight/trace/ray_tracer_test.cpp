#include "steadylight/trace/ray_tracer.h"

#include <gtest/gtest.h>

#include "steadylight/base/rng.h"
#include "steadylight/base/sampling.h"
#include "support/scene_builder.h"

namespace steadylight {
namespace {

using testing::add_material;
using testing::add_object;
using testing::make_empty_scene;

/// A floor quad (static) and a unit sphere (dynamic) moving along +x by one unit per frame.
SceneDesc floor_and_moving_sphere() {
    SceneDesc desc = make_empty_scene({0, 5, 0}, {0, 0, 0});
    desc.frame_count = 10;
    desc.fps = 1;
    const int white = add_material(desc, {});
    add_object(desc, make_quad({-10, 0, -10}, {0, 0, 20}, {20, 0, 0}), white);
    const int sphere = add_object(desc, Sphere{{0, 0, 0}, 1}, white);
    desc.objects[size_t(sphere)].placement[0].translation_track =
        Track<Vec3>{Interpolation::linear, {0, 10}, {{0, 2, 0}, {10, 2, 0}}};
    return desc;
}

const Ray down_at_origin{{0, 10, 0}, {0, -1, 0}};

TEST(RayTracer, MissingEverythingGivesNoHit) {
    const Scene scene(floor_and_moving_sphere());
    const RayTracer tracer(scene, scene.evaluate(0));
    EXPECT_FALSE(tracer.intersect({{0, 10, 0}, {0, 1, 0}}).has_value());
}

TEST(RayTracer, DynamicObjectIsHitBeforeTheFloor) {
    const Scene scene(floor_and_moving_sphere());
    const RayTracer tracer(scene, scene.evaluate(0));
    const std::optional<Hit> hit = tracer.intersect(down_at_origin);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->object, 1);
    EXPECT_NEAR(hit->t, 7, 1e-4f);  // sphere top at y = 3
}

TEST(RayTracer, StaticOnlyRaysPassThroughDynamicObjects) {
    const Scene scene(floor_and_moving_sphere());
    const RayTracer tracer(scene, scene.evaluate(0));
    const std::optional<Hit> hit = tracer.intersect(down_at_origin, Visibility::static_only);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->object, 0);
    EXPECT_NEAR(hit->t, 10, 1e-4f);
    EXPECT_TRUE(tracer.occluded(down_at_origin, Visibility::everything));
}

// Opaque-only rays pass through glass, static or moving, and meet everything else.
TEST(RayTracer, OpaqueOnlyRaysPassThroughGlass) {
    const int glass_material = 1;  // added after floor_and_moving_sphere's white
    {                              // a static glass block over the moving (opaque) sphere
        SceneDesc desc = floor_and_moving_sphere();
        ASSERT_EQ(add_material(desc, {.type = MaterialType::dielectric}), glass_material);
        add_object(desc, make_box({0, 5, 0}, {1, 1, 1}), glass_material);
        const Scene scene(std::move(desc));
        const RayTracer tracer(scene, scene.evaluate(0));
        EXPECT_NEAR(tracer.intersect(down_at_origin)->t, 4.5f, 1e-4f);  // the block's top
        EXPECT_NEAR(tracer.intersect(down_at_origin, Visibility::static_only)->t, 4.5f, 1e-4f);
        EXPECT_NEAR(tracer.intersect(down_at_origin, Visibility::opaque)->t, 7.0f, 1e-4f);  // the sphere
        EXPECT_NEAR(tracer.intersect(down_at_origin, Visibility::static_opaque)->t, 10.0f, 1e-4f);
        EXPECT_FALSE(tracer.occluded({{0, 10, 0}, {0, -1, 0}, 6.5f}, Visibility::opaque));
    }
    {  // the moving sphere made of glass
        SceneDesc desc = floor_and_moving_sphere();
        ASSERT_EQ(add_material(desc, {.type = MaterialType::dielectric}), glass_material);
        desc.objects[1].material = glass_material;
        const Scene scene(std::move(desc));
        const RayTracer tracer(scene, scene.evaluate(0));
        EXPECT_NEAR(tracer.intersect(down_at_origin)->t, 7.0f, 1e-4f);
        EXPECT_NEAR(tracer.intersect(down_at_origin, Visibility::opaque)->t, 10.0f, 1e-4f);
        EXPECT_FALSE(tracer.occluded({{0, 10, 0}, {0, -1, 0}, 9.5f}, Visibility::opaque));
        EXPECT_TRUE(tracer.occluded({{0, 10, 0}, {0, -1, 0}, 9.5f}, Visibility::everything));
    }
}

TEST(RayTracer, OcclusionStopsAtTmax) {
    const Scene scene(floor_and_moving_sphere());
    const RayTracer tracer(scene, scene.evaluate(0));
    EXPECT_FALSE(tracer.occluded({{0, 10, 0}, {0, -1, 0}, 6.5f}));
    EXPECT_TRUE(tracer.occluded({{0, 10, 0}, {0, -1, 0}, 7.5f}));
}

// For a ray that the static objects do not stop, occluded_by_dynamic() is occluded()'s answer:
// rays from points on the floor to points above the sphere's path, a static ball in the way of
// some and the moving sphere in the way of others, at three frames.
TEST(RayTracer, OccludedByDynamicAnswersAsOccludedWhereNothingStaticStops) {
    SceneDesc desc = floor_and_moving_sphere();
    add_object(desc, Sphere{{-4, 1.5f, 0}, 0.75f}, 0);
    const Scene scene(std::move(desc));
    RayTracer tracer(scene, scene.evaluate(0));
    long stopped_by_static = 0, stopped_by_dynamic = 0, open = 0;
    for (const int frame : {0, 3, 9}) {
        tracer.set_frame(scene.evaluate(frame));
        for (int i = 0; i < 40; ++i)
            for (int j = 0; j < 40; ++j) {
                const Vec3 floor{-10 + 0.5f * float(i), 0, -4 + 0.2f * float(j)};
                const Vec3 above{-2 + 0.1f * float(j), 4, 0.05f * float(i)};
                const Ray ray = spawn_ray_to(floor, {0, 1, 0}, above);
                if (tracer.occluded(ray, Visibility::static_only)) {
                    EXPECT_TRUE(tracer.occluded(ray));
                    ++stopped_by_static;
                    continue;
                }
                ASSERT_EQ(tracer.occluded_by_dynamic(ray), tracer.occluded(ray)) << frame << " " << i << " " << j;
                tracer.occluded(ray) ? ++stopped_by_dynamic : ++open;
            }
    }
    // Each kind of ray is there.
    EXPECT_GT(stopped_by_static, 100);
    EXPECT_GT(stopped_by_dynamic, 100);
    EXPECT_GT(open, 100);
}

TEST(RayTracer, SetFrameMovesDynamicObjects) {
    const Scene scene(floor_and_moving_sphere());
    RayTracer tracer(scene, scene.evaluate(0));
    tracer.set_frame(scene.evaluate(5));  // the sphere is now at x = 5
    EXPECT_EQ(tracer.intersect(down_at_origin)->object, 0);
    const std::optional<Hit> hit = tracer.intersect({{5, 10, 0}, {0, -1, 0}});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->object, 1);
}

TEST(RayTracer, RayFromInsideASphereHitsItsFarSide) {
    const Scene scene(floor_and_moving_sphere());
    const RayTracer tracer(scene, scene.evaluate(0));
    const std::optional<Hit> hit = tracer.intersect({{0, 2, 0}, {1, 0, 0}});
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 1, 1e-4f);
}

// A moving sphere primitive's own points' rays that head out of it are not asked of Embree
// (RayTracer::may_hit_instances): each kind of ray about the surface still meets what it meets.
// The sphere is placed rotated and evenly scaled, where most rays heading out are spared Embree,
// and unevenly scaled, an ellipsoid whose rays are judged against the sphere about it. Rays start
// a thousandth of the radius off the surface, as a ray offset puts them.
TEST(RayTracer, RaysAboutAMovingSphereMeetItAsTheyShould) {
    for (const Vec3 scale : {Vec3{1.5f, 1.5f, 1.5f}, Vec3{2, 1, 0.5f}}) {
        SceneDesc desc = floor_and_moving_sphere();
        desc.objects[1].placement[0].scale = scale;
        desc.objects[1].placement[0].rotation = Quat::from_axis_angle(normalize(Vec3{1, 2, 3}), 0.7f);
        const Scene scene(std::move(desc));
        RayTracer tracer(scene, scene.evaluate(0));
        Pcg32 rng(3);
        int heading_out = 0, from_inside = 0, heading_in = 0;
        for (const int frame : {0, 3, 9}) {
            const FrameState state = scene.evaluate(frame);
            tracer.set_frame(state);
            const Transform& world_from_object = state.world_from_object[1];
            for (int i = 0; i < 3000; ++i) {
                const Vec3 on_unit = sample_uniform_sphere(rng.next_vec2());
                const Vec3 p = world_from_object.point(on_unit), n = normalize(world_from_object.normal(on_unit));
                Vec3 d = sample_uniform_sphere(rng.next_vec2());
                if (std::abs(dot(d, n)) < 0.05f) continue;  // grazing: either answer is the surface's
                const bool out = dot(d, n) > 0;
                const int kind = i % 2;
                if (out && kind == 0) {
                    // From just outside, heading out: the sphere is behind the ray.
                    const std::optional<Hit> hit = tracer.intersect({p + n * 1e-3f, d});
                    ASSERT_TRUE(!hit || hit->object != 1) << frame << " " << i;
                    ASSERT_FALSE(tracer.occluded({p + n * 1e-3f, d, 0.5f})) << frame << " " << i;
                    ++heading_out;
                } else {
                    // From just inside heading out, or from just outside aimed at a point inside:
                    // it meets the sphere.
                    if (!out) {
                        const Vec3 inside = sample_uniform_sphere(rng.next_vec2()) * (0.9f * rng.next_float());
                        d = normalize(world_from_object.point(inside) - (p + n * 1e-3f));
                    }
                    const Ray ray{out ? p - n * 1e-3f : p + n * 1e-3f, d};
                    const std::optional<Hit> hit = tracer.intersect(ray);
                    ASSERT_TRUE(hit && hit->object == 1) << frame << " " << i;
                    ASSERT_TRUE(tracer.occluded(ray)) << frame << " " << i;
                    out ? ++from_inside : ++heading_in;
                }
            }
        }
        EXPECT_GT(heading_out, 1000);
        EXPECT_GT(from_inside, 1000);
        EXPECT_GT(heading_in, 1000);
    }
}

// A moving object placed by a chain that shears (a rotated child of an unevenly scaled parent)
// stretches farther than its longest placed axis: rays meeting it near its farthest points still
// meet it, from outside and from its own surface, and the sphere about it holds it.
TEST(RayTracer, AShearedMovingObjectIsMetToItsFarthestPoints) {
    SceneDesc desc = floor_and_moving_sphere();
    AnimatedTrs child;
    child.rotation = Quat::from_axis_angle({0, 0, 1}, 0.7853982f);
    desc.objects[1].placement[0].scale = {2, 1, 1};
    desc.objects[1].placement.push_back(child);
    const Scene scene(std::move(desc));
    const FrameState state = scene.evaluate(4);
    const RayTracer tracer(scene, state);
    const Transform& world_from_object = state.world_from_object[1];
    const Vec3 center = world_from_object.point({});
    Pcg32 rng(5);
    int farthest_seen = 0;
    for (int i = 0; i < 4000; ++i) {
        const Vec3 p = world_from_object.point(sample_uniform_sphere(rng.next_vec2()));
        const Vec3 out = p - center;
        if (length(out) < 1.9f) continue;  // near the tips, 2 from the centre; its longest axis is 1.58
        ++farthest_seen;
        ASSERT_LE(length(out), tracer.dynamic_bounds()[0].radius) << i;
        // A ray across the object just inside that point, perpendicular to the way out.
        const Vec3 across = normalize(cross(out, Vec3{0, 1, 0}));  // level: clear of the floor
        const Vec3 inside = center + out * 0.99f;
        const Ray ray{inside - across * 5.0f, across};
        const std::optional<Hit> hit = tracer.intersect(ray);
        ASSERT_TRUE(hit && hit->object == 1) << i;
        ASSERT_TRUE(tracer.occluded(ray)) << i;
        // And a ray from just inside that point out of the object, through its tip.
        const Ray leaving{inside, normalize(out)};
        ASSERT_TRUE(tracer.intersect(leaving).has_value() && tracer.intersect(leaving)->object == 1) << i;
    }
    EXPECT_GT(farthest_seen, 50);
}

TEST(RayTracer, UnevenlyScaledStaticSphereIsAnEllipsoid) {
    SceneDesc desc = make_empty_scene({0, 5, 0}, {0, 0, 0});
    add_object(desc, Sphere{{0, 0, 0}, 1}, add_material(desc, {}));
    desc.objects[0].placement[0].scale = {3, 1, 1};
    const Scene scene(std::move(desc));
    const RayTracer tracer(scene, scene.evaluate(0));
    const std::optional<Hit> hit = tracer.intersect({{-10, 0, 0}, {1, 0, 0}});
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 7, 1e-3f);
}

}  // namespace
}  // namespace steadylight
