// glTF 2.0 import (.gltf and .glb, through tinygltf): the node hierarchy with its transforms,
// triangle meshes, materials (base colour as Lambertian reflectance; emissive factor times
// KHR_materials_emissive_strength as an area light; KHR_materials_transmission with ior as a
// smooth dielectric), the first perspective camera, and node animations (translation, rotation,
// scale; LINEAR, STEP, CUBICSPLINE). A node that is animated, or under an animated node, is
// dynamic. What is ignored is listed in docs/gltf.md and logged as a warning.
#pragma once

#include <string>

#include "steadylight/scene/scene_desc.h"

namespace steadylight {

/// Adds the glTF file's materials and objects to `desc`; when `desc` has no camera yet
/// (`has_camera` false) and the file has one, it becomes the scene's camera. Returns the length
/// of the file's longest animation in seconds (0 when nothing is animated).
float append_gltf(const std::string& path, SceneDesc& desc, bool& has_camera);

}  // namespace steadylight
