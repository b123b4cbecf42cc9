// glTF node placements and animations (glTF 2.0 §3.5.3 and §3.11): each node's TRS (or
// decomposed matrix) as an AnimatedTrs, with translation, rotation and scale channels attached
// as LINEAR, STEP or CUBICSPLINE tracks.
#pragma once

#include <optional>
#include <vector>

#include "steadylight/scene/animation.h"
#include "steadylight/scene/gltf_file.h"

namespace steadylight::gltf {

/// The node's rest placement: its matrix decomposed into T * R * S, or its TRS.
AnimatedTrs node_placement(const tinygltf::Node& node);

/// Attaches every channel of every animation to `placements`, one per node; returns the
/// longest animation's length in seconds.
float apply_animations(const GltfFile& file, std::vector<AnimatedTrs>& placements);

/// The frame rate the animations were sampled at, when every LINEAR or STEP sampler with three
/// or more keys has them evenly spaced at one common rate of film or video (23.976 to 120 fps):
/// what Blender's exporter writes by default (a key every frame). Otherwise nothing.
std::optional<float> sampled_frame_rate(const GltfFile& file);

}  // namespace steadylight::gltf
