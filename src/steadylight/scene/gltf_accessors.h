// Reading glTF accessors (glTF 2.0 §3.6) into steadylight types, bounds-checked against their
// buffer views and buffers, because tinygltf 2.7 checks only that buffers hold their byteLength.
// Every error is an InputError naming the file, the user of the accessor and its index.
#pragma once

#include <string>
#include <vector>

#include "steadylight/base/transform.h"
#include "steadylight/base/vec.h"
#include "steadylight/scene/gltf_file.h"
#include "steadylight/scene/texture.h"

namespace steadylight::gltf {

/// A float SCALAR accessor.
std::vector<float> read_floats(const GltfFile& file, int index, const std::string& user);
/// A float VEC3 accessor.
std::vector<Vec3> read_vec3s(const GltfFile& file, int index, const std::string& user);
/// A VEC4 accessor of rotations: floats or normalised integers (§5.6 "animation.sampler.output").
std::vector<Quat> read_quats(const GltfFile& file, int index, const std::string& user);
/// TEXCOORD_n: VEC2 of floats or normalised unsigned bytes or shorts.
std::vector<Vec2> read_texcoords(const GltfFile& file, int index, const std::string& user);
/// COLOR_0 or TANGENT: VEC3 or VEC4 of floats or normalised unsigned integers; a VEC3's fourth
/// component is `w_default`.
std::vector<Rgba> read_vec4s(const GltfFile& file, int index, const std::string& user, float w_default);
/// Vertex indices (unsigned byte, short or int), each checked against `vertex_count`.
std::vector<int> read_indices(const GltfFile& file, int index, const std::string& user, size_t vertex_count);

}  // namespace steadylight::gltf
