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

/// The frame rate the animations were sampled at: 1 / the key spacing, when every LINEAR or
/// STEP sampler with three or more keys has them evenly spaced (within 1e-3 of the spacing) at
/// one common spacing, and that rate lies in [10, 240] fps. A rate within 5e-4 of a whole number
/// is made whole (39.0003 -> 39); others stay as measured (29.97). Blender's exporter writes a
/// key every frame by default. Otherwise (no such sampler, uneven or disagreeing spacings, keys
/// far apart) nothing.
std::optional<float> sampled_frame_rate(const GltfFile& file);

}  // namespace steadylight::gltf
