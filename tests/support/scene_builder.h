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

}  // namespace steadylight::testing
