// Small scenes built in code for tests: a SceneDesc with a camera, materials and objects added
// one call at a time.
#pragma once

#include "steadylight/scene/scene_desc.h"
#include "steadylight/scene/shapes.h"

namespace steadylight::testing {

/// A scene with a camera at `eye` looking at `target`, `width` x `height` pixels, no objects.
inline SceneDesc make_empty_scene(Vec3 eye, Vec3 target, int width = 16, int height = 16, float fov_y_deg = 40) {
    SceneDesc desc;
    desc.name = "test";
    desc.source_file = "(test scene)";
    AnimatedTrs camera;
    camera.translation = eye;
    const Vec3 back = normalize(eye - target);
    const Vec3 helper = std::abs(back.y) > 0.99f ? Vec3{0, 0, 1} : Vec3{0, 1, 0};
    const Vec3 right = normalize(cross(helper, back));
    camera.rotation = Quat::from_basis(right, cross(back, right), back);
    desc.camera = {{camera}, fov_y_deg, width, height};
    return desc;
}

inline int add_material(SceneDesc& desc, MaterialDesc material) {
    desc.materials.push_back(material);
    return int(desc.materials.size()) - 1;
}

/// Adds an object with the given geometry and material index; returns its index.
inline int add_object(SceneDesc& desc, Geometry geometry, int material, Rgb emission = {}) {
    ObjectDesc object;
    object.name = "object" + std::to_string(desc.objects.size());
    object.geometry = std::move(geometry);
    object.material = material;
    object.emission = emission;
    object.placement = {AnimatedTrs{}};
    desc.objects.push_back(std::move(object));
    return int(desc.objects.size()) - 1;
}

/// A glass ball of radius 0.5 at the origin, index 1 (no refraction, no reflection), absorbing
/// so that light keeps `attenuation_color` over 0.5 units, in front of a large light of radiance
/// 1 at z = -2; the camera at z = 3 sees the ball's centre with a 0.5 degree view, 4 x 4 pixels.
/// Every camera ray travels 1 unit inside (within 0.14%): the pixels are attenuation_color^2.
inline SceneDesc absorbing_ball_before_light(Rgb attenuation_color) {
    SceneDesc desc = make_empty_scene({0, 0, 3}, {0, 0, 0}, 4, 4, 0.5f);
    MaterialDesc glass{.type = MaterialType::dielectric, .ior = 1, .roughness = 0};
    glass.attenuation_color = attenuation_color;
    glass.attenuation_distance = 0.5f;
    add_object(desc, Sphere{{0, 0, 0}, 0.5f}, add_material(desc, glass));
    add_object(desc, make_quad({-5, -5, -2}, {10, 0, 0}, {0, 10, 0}), add_material(desc, {}), {1, 1, 1});
    return desc;
}

/// Two lit rooms side by side, [0,3.4] and [4.6,8] in x, open towards the camera at z = 0, with
/// a ball moving in the first only, 48 x 24 pixels, 2 frames. No light path passes from one room
/// to the other, and the wall between them is thicker than the photon density estimates' radius
/// (0.5), so no estimate reaches across. The camera's right is -x: the room without the ball
/// fills the left half of the image.
inline SceneDesc two_rooms_one_moving_ball() {
    SceneDesc desc = make_empty_scene({4, 1.5f, -6}, {4, 1.5f, 0}, 48, 24, 40);
    desc.name = "two_rooms";
    desc.frame_count = 2;
    const int white = add_material(desc, {.reflectance = {0.7f, 0.7f, 0.7f}});
    add_object(desc, make_quad({0, 0, 0}, {0, 0, 4}, {8, 0, 0}), white);  // floor
    add_object(desc, make_quad({0, 3, 0}, {8, 0, 0}, {0, 0, 4}), white);  // ceiling
    add_object(desc, make_quad({0, 0, 4}, {0, 3, 0}, {8, 0, 0}), white);  // back
    add_object(desc, make_quad({0, 0, 0}, {0, 3, 0}, {0, 0, 4}), white);  // left
    add_object(desc, make_quad({8, 0, 0}, {0, 0, 4}, {0, 3, 0}), white);  // right
    add_object(desc, make_box({4, 1.5f, 2}, {1.2f, 3, 4}), white);        // partition
    for (const float x : {1.75f, 5.75f})
        add_object(desc, make_quad({x, 2.95f, 1.75f}, {0.5f, 0, 0}, {0, 0, 0.5f}), white, {30, 30, 30});
    add_object(desc, Sphere{{0, 0, 0}, 0.4f}, white);
    desc.objects.back().placement[0].translation_track =
        Track<Vec3>{Interpolation::linear, {0, 1}, {{1.5f, 0.4f, 2}, {2.5f, 0.4f, 2}}};
    return desc;
}

/// A grey, a glass and a mirror ball (radius 0.55, at x = -1.4, 0 and 1.4, y = 0.3) in front of
/// a uniform blue world that lights them, and a small grey ball moving below them from x = -1.5
/// to 1.5 over 2 frames; the camera stands still at z = 5, 32 x 24 pixels, and sees the world
/// around them.
inline SceneDesc balls_before_the_world() {
    SceneDesc desc = make_empty_scene({0, 0, 5}, {0, 0, 0}, 32, 24, 40);
    desc.name = "balls";
    desc.frame_count = 2;
    desc.fps = 1;  // frame 1 at 1 s, where the track ends
    const int grey = add_material(desc, {.reflectance = {0.6f, 0.6f, 0.6f}});
    add_object(desc, Sphere{{-1.4f, 0.3f, 0}, 0.55f}, grey);
    add_object(desc, Sphere{{0, 0.3f, 0}, 0.55f},
               add_material(desc, {.type = MaterialType::dielectric, .ior = 1.5f, .roughness = 0}));
    add_object(desc, Sphere{{1.4f, 0.3f, 0}, 0.55f},
               add_material(desc, {.type = MaterialType::mirror, .reflectance = {0.9f, 0.9f, 0.9f}}));
    add_object(desc, Sphere{{0, 0, 0}, 0.25f}, grey);
    desc.objects.back().placement[0].translation_track =
        Track<Vec3>{Interpolation::linear, {0, 1}, {{-1.5f, -1.1f, 0}, {1.5f, -1.1f, 0}}};
    desc.world = WorldDesc::uniform({0.2f, 0.3f, 0.5f});
    return desc;
}

}  // namespace steadylight::testing
