#include "steadylight/shading/mirror_images.h"

#include <gtest/gtest.h>

#include "support/scene_builder.h"

namespace steadylight {
namespace {

using testing::add_material;
using testing::add_object;
using testing::make_empty_scene;

TEST(FlatMirrors, OnlyFlatStaticMirrorsAreFoundWherePlaced) {
    SceneDesc desc = make_empty_scene({0, 1, 5}, {0, 1, 0});
    const int mirror = add_material(desc, {.type = MaterialType::mirror, .reflectance = {0.9f, 0.9f, 0.9f}});
    const int white = add_material(desc, {});
    const int flat = add_object(desc, make_quad({0, 0, 0}, {0, 2, 0}, {0, 0, 2}), mirror);
    desc.objects[size_t(flat)].placement[0].translation = {3, 0, 0};
    add_object(desc, make_quad({0, 0, 0}, {2, 0, 0}, {0, 0, 2}), white);  // flat, but not a mirror
    add_object(desc, Sphere{{0, 1, 0}, 0.5f}, mirror);                    // a mirror, not flat
    add_object(desc, make_box({0, 1, 0}, {1, 1, 1}), mirror);             // six planes
    const int moving = add_object(desc, make_quad({0, 0, 0}, {0, 2, 0}, {0, 0, 2}), mirror);
    desc.objects[size_t(moving)].placement[0].translation_track =
        Track<Vec3>{Interpolation::linear, {0, 1}, {{-3, 0, 0}, {-2, 0, 0}}};
    desc.frame_count = 2;
    const Scene scene(desc);
    const std::vector<MirrorPlane> found = flat_mirrors(scene, scene.evaluate(0));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].object, flat);
    EXPECT_FLOAT_EQ(found[0].point.x, 3);
    EXPECT_NEAR(std::abs(found[0].normal.x), 1, 1e-6);
}

}  // namespace
}  // namespace steadylight
