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
/// A file whose animation keys are sampled evenly (as Blender exports by default; see
/// gltf::sampled_frame_rate) sets `desc.fps` to 1 / their spacing and `desc.fps_source` to
/// FpsSource::gltf_keys.
float append_gltf(const std::string& path, SceneDesc& desc, bool& has_camera, const InputFolder& inputs = {});

/// True for a path ending in .gltf or .glb (in any case).
bool is_gltf_file(const std::string& path);

/// The frames that cover an animation of `duration_s` at `fps`: 1 + floor(duration_s * fps).
int frames_covering(float duration_s, float fps);

/// A whole scene from one glTF file (`steadylight render scene.glb`): its objects, lights and
/// camera (which it must have), frames covering its longest animation at its sampled key rate
/// or 24 fps, named after the file. Throws InputError like load_scene_desc.
SceneDesc load_gltf_scene_desc(const std::string& path, bool confine_inputs = false);

}  // namespace steadylight
