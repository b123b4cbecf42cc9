// glTF 2.0 import (gltf_loader.h) in three phases: every node's local placement, then the
// animations that attach tracks to those placements, then a walk of the default scene that
// copies each node's placement chain into its objects, the camera and the lights. Accessors are
// bounds-checked here, because tinygltf 2.7 checks only that buffers hold their byteLength.
// Spec: https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html
#include "steadylight/scene/gltf_loader.h"

#include <spdlog/spdlog.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <span>
#include <utility>

#include "steadylight/base/error.h"

namespace steadylight {
namespace {

constexpr float deg_per_rad = 180 / pi;

/// "node 3 \"Ball\"", or "node 3" for an unnamed element.
std::string describe(const std::string& kind, size_t index, const std::string& name) {
    return kind + " " + std::to_string(index) + (name.empty() ? "" : " \"" + name + "\"");
}

/// The file being imported, for reading its data and for messages about it.
struct GltfFile {
    std::string path;
    tinygltf::Model model;
    mutable std::set<std::string> warned;

    /// Throws InputError at "<path>: <element>".
    [[noreturn]] void fail(const std::string& element, const std::string& what) const {
        throw InputError(path + ": " + element, what);
    }
    /// Logs "<path>: <what> (<element>)" the first time `what` comes up, so that a feature
    /// used by a thousand materials is reported once.
    void warn_once(const std::string& what, const std::string& element) const {
        if (!warned.insert(what).second) return;
        if (element.empty()) spdlog::warn("{}: {}", path, what);
        else spdlog::warn("{}: {} ({})", path, what, element);
    }
};

// ---------------------------------------------------------------------------------------------
// Reading the file

std::string lowercase_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

std::string trim_newlines(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    return s;
}

// Textures are ignored, so there is no point in decoding their images.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                const unsigned char*, int, void*) {
    return true;
}

tinygltf::Model load_model(const std::string& path) {
    const std::string ext = lowercase_extension(path);
    if (ext != ".gltf" && ext != ".glb")
        throw InputError(path,
                         "unknown glTF file extension \"" + ext + "\" (expected .gltf or .glb)");
    if (!std::filesystem::is_regular_file(path)) throw InputError(path, "file not found");
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(skip_image, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const bool ok = ext == ".glb" ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                                  : loader.LoadASCIIFromFile(&model, &err, &warn, path);
    if (!warn.empty()) spdlog::warn("{}: {}", path, trim_newlines(warn));
    if (!ok) throw InputError(path, err.empty() ? "cannot read the glTF file" : trim_newlines(err));
    return model;
}

// ---------------------------------------------------------------------------------------------
// Accessors

/// An accessor checked to lie inside its buffer: element i starts at `data + i * stride`.
struct AccessorView {
    const unsigned char* data = nullptr;
    size_t stride = 0;
    size_t count = 0;
    int component_type = 0;
    size_t component_size = 0;
    int type = 0;
    bool normalized = false;

    const unsigned char* at(size_t i, int c) const {
        return data + i * stride + size_t(c) * component_size;
    }
};

template <class T>
T load_unaligned(const unsigned char* p) {
    T value;
    std::memcpy(&value, p, sizeof value);
    return value;
}

/// Component c of element i as a float; normalised integers map to [0, 1] or [-1, 1] as in
/// glTF 2.0 §3.11 "Animations" (the same rule as for vertex attributes).
float read_component(const AccessorView& view, size_t i, int c) {
    const unsigned char* p = view.at(i, c);
    const auto scale = [&](float value, float max_value) {
        return view.normalized ? std::max(value / max_value, -1.0f) : value;
    };
    switch (view.component_type) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return load_unaligned<float>(p);
        case TINYGLTF_COMPONENT_TYPE_BYTE: return scale(load_unaligned<int8_t>(p), 127);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return scale(load_unaligned<uint8_t>(p), 255);
        case TINYGLTF_COMPONENT_TYPE_SHORT: return scale(load_unaligned<int16_t>(p), 32767);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return scale(load_unaligned<uint16_t>(p), 65535);
    }
    return 0;
}

uint32_t read_unsigned(const AccessorView& view, size_t i) {
    const unsigned char* p = view.at(i, 0);
    switch (view.component_type) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return load_unaligned<uint8_t>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load_unaligned<uint16_t>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load_unaligned<uint32_t>(p);
    }
    return 0;
}

/// True when `count` elements of `element_size` bytes, `stride` apart from `offset`, fit in
/// `length` bytes; written so that no product can overflow.
bool fits(size_t offset, size_t count, size_t stride, size_t element_size, size_t length) {
    if (count == 0) return offset <= length;
    if (offset > length || element_size > length - offset) return false;
    return count - 1 <= (length - offset - element_size) / stride;
}

/// The bytes of the accessor's bufferView, checked to lie inside their buffer.
std::span<const unsigned char> buffer_view_bytes(const GltfFile& file,
                                                 const tinygltf::Accessor& accessor,
                                                 const std::string& where) {
    const tinygltf::Model& model = file.model;
    if (accessor.bufferView < 0 || size_t(accessor.bufferView) >= model.bufferViews.size())
        file.fail(where, "accessor has no valid bufferView");
    const tinygltf::BufferView& view = model.bufferViews[size_t(accessor.bufferView)];
    const std::string name = "bufferView " + std::to_string(accessor.bufferView);
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
        file.fail(where, name + " has no valid buffer");
    const std::vector<unsigned char>& buffer = model.buffers[size_t(view.buffer)].data;
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
        file.fail(where, name + " reaches past the end of its buffer");
    return {buffer.data() + view.byteOffset, view.byteLength};
}

AccessorView view_accessor(const GltfFile& file, int index, const std::string& user) {
    const std::string where = user + ", accessor " + std::to_string(index);
    if (index < 0 || size_t(index) >= file.model.accessors.size())
        file.fail(where, "accessor index out of range");
    const tinygltf::Accessor& accessor = file.model.accessors[size_t(index)];
    if (accessor.sparse.isSparse) file.fail(where, "sparse accessors are not supported");
    const std::span<const unsigned char> bytes = buffer_view_bytes(file, accessor, where);
    const int component_size = tinygltf::GetComponentSizeInBytes(uint32_t(accessor.componentType));
    const int components = tinygltf::GetNumComponentsInType(uint32_t(accessor.type));
    if (component_size <= 0 || components <= 0) file.fail(where, "unknown componentType or type");
    const size_t element_size = size_t(component_size) * size_t(components);
    const size_t byte_stride = file.model.bufferViews[size_t(accessor.bufferView)].byteStride;
    const size_t stride = byte_stride ? byte_stride : element_size;
    if (stride < element_size) file.fail(where, "byteStride is smaller than one element");
    if (!fits(accessor.byteOffset, accessor.count, stride, element_size, bytes.size()))
        file.fail(where, "accessor reaches past the end of its bufferView");
    return {.data = bytes.data() + accessor.byteOffset,
            .stride = stride,
            .count = accessor.count,
            .component_type = accessor.componentType,
            .component_size = size_t(component_size),
            .type = accessor.type,
            .normalized = accessor.normalized};
}

/// Views an accessor that must have element `type` and one of `component_types`, which
/// `expected` spells out for the message ("float VEC3").
AccessorView view_typed(const GltfFile& file, int index, const std::string& user, int type,
                        std::initializer_list<int> component_types, const std::string& expected) {
    const AccessorView view = view_accessor(file, index, user);
    const bool component_ok = std::find(component_types.begin(), component_types.end(),
                                        view.component_type) != component_types.end();
    if (view.type != type || !component_ok)
        file.fail(user, "accessor " + std::to_string(index) + " must be " + expected);
    return view;
}

std::vector<float> read_floats(const GltfFile& file, int index, const std::string& user) {
    const AccessorView view = view_typed(file, index, user, TINYGLTF_TYPE_SCALAR,
                                         {TINYGLTF_COMPONENT_TYPE_FLOAT}, "float SCALAR");
    std::vector<float> values(view.count);
    for (size_t i = 0; i < view.count; ++i) values[i] = read_component(view, i, 0);
    return values;
}

std::vector<Vec3> read_vec3s(const GltfFile& file, int index, const std::string& user) {
    const AccessorView view = view_typed(file, index, user, TINYGLTF_TYPE_VEC3,
                                         {TINYGLTF_COMPONENT_TYPE_FLOAT}, "float VEC3");
    std::vector<Vec3> values(view.count);
    for (size_t i = 0; i < view.count; ++i)
        values[i] = {read_component(view, i, 0), read_component(view, i, 1),
                     read_component(view, i, 2)};
    return values;
}

/// Rotations may be floats or normalised integers (glTF 2.0 §5.6 "animation.sampler.output").
std::vector<Quat> read_quats(const GltfFile& file, int index, const std::string& user) {
    const AccessorView view =
        view_typed(file, index, user, TINYGLTF_TYPE_VEC4,
                   {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                    TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                    TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                   "VEC4 of floats or normalised integers");
    if (view.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT && !view.normalized)
        file.fail(user,
                  "accessor " + std::to_string(index) + ": integer rotations must be normalized");
    std::vector<Quat> values(view.count);
    for (size_t i = 0; i < view.count; ++i)
        values[i] = {read_component(view, i, 0), read_component(view, i, 1),
                     read_component(view, i, 2), read_component(view, i, 3)};
    return values;
}

std::vector<int> read_indices(const GltfFile& file, int index, const std::string& user,
                              size_t vertex_count) {
    const AccessorView view =
        view_typed(file, index, user, TINYGLTF_TYPE_SCALAR,
                   {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                    TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                   "unsigned byte, short or int SCALAR");
    std::vector<int> indices(view.count);
    for (size_t i = 0; i < view.count; ++i) {
        const uint32_t vertex = read_unsigned(view, i);
        if (vertex >= vertex_count)
            file.fail(user, "index " + std::to_string(vertex) + " out of range (" +
                                std::to_string(vertex_count) + " vertices)");
        indices[i] = int(vertex);
    }
    return indices;
}

// ---------------------------------------------------------------------------------------------
// Meshes

/// Triangle lists from strips and fans, in the vertex order of glTF 2.0 §3.7.2.1.
std::vector<int> triangulate(const std::vector<int>& v, int mode) {
    if (mode == TINYGLTF_MODE_TRIANGLES) return v;
    std::vector<int> triangles;
    for (size_t i = 0; i + 2 < v.size(); ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_FAN)
            triangles.insert(triangles.end(), {v[i + 1], v[i + 2], v[0]});
        else if (i % 2 == 0) triangles.insert(triangles.end(), {v[i], v[i + 1], v[i + 2]});
        else triangles.insert(triangles.end(), {v[i], v[i + 2], v[i + 1]});
    }
    return triangles;
}

void warn_ignored_attributes(const GltfFile& file, const tinygltf::Primitive& primitive,
                             const std::string& where) {
    if (!primitive.targets.empty()) file.warn_once("morph targets are ignored", where);
    if (primitive.attributes.contains("COLOR_0"))
        file.warn_once("vertex colours (COLOR_0) are ignored", where);
}

/// The primitive's vertices in drawing order: its indices, or 0, 1, 2, ... without them.
std::vector<int> primitive_vertices(const GltfFile& file, const tinygltf::Primitive& primitive,
                                    const std::string& where, size_t vertex_count) {
    if (primitive.indices >= 0)
        return read_indices(file, primitive.indices, where + ", indices", vertex_count);
    std::vector<int> vertices(vertex_count);
    std::iota(vertices.begin(), vertices.end(), 0);
    return vertices;
}

/// The primitive's triangles, or nothing for points, lines and primitives without positions.
std::optional<TriangleMesh> read_primitive(const GltfFile& file,
                                           const tinygltf::Primitive& primitive,
                                           const std::string& where) {
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode < TINYGLTF_MODE_TRIANGLES || mode > TINYGLTF_MODE_TRIANGLE_FAN) {
        file.warn_once("point and line primitives are ignored", where);
        return std::nullopt;
    }
    const auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end()) {
        file.warn_once("primitives without POSITION are ignored", where);
        return std::nullopt;
    }
    warn_ignored_attributes(file, primitive, where);
    TriangleMesh mesh;
    mesh.positions = read_vec3s(file, position->second, where + ", POSITION");
    if (const auto normal = primitive.attributes.find("NORMAL");
        normal != primitive.attributes.end()) {
        mesh.normals = read_vec3s(file, normal->second, where + ", NORMAL");
        if (mesh.normals.size() != mesh.positions.size())
            file.fail(where, "NORMAL and POSITION counts differ");
    }
    mesh.indices =
        triangulate(primitive_vertices(file, primitive, where, mesh.positions.size()), mode);
    if (mesh.indices.size() % 3 != 0)
        file.fail(where, "triangle vertex count " + std::to_string(mesh.indices.size()) +
                             " is not a multiple of 3");
    return mesh;
}

std::string object_name(const tinygltf::Node& node, const tinygltf::Mesh& mesh, int node_index,
                        size_t primitive) {
    std::string name = !node.name.empty()   ? node.name
                       : !mesh.name.empty() ? mesh.name
                                            : "node " + std::to_string(node_index);
    if (mesh.primitives.size() > 1) name += "#" + std::to_string(primitive);
    return name;
}

// ---------------------------------------------------------------------------------------------
// Materials

/// What a glTF material becomes: an entry in SceneDesc::materials plus the emission that the
/// objects using it carry (emission belongs to objects in SceneDesc, to materials in glTF).
struct ImportedMaterial {
    int index = 0;
    Rgb emission;
    bool two_sided = false;
};

/// The number `key` inside extension `name`, or `fallback` when either is absent.
double extension_number(const tinygltf::ExtensionMap& extensions, const std::string& name,
                        const std::string& key, double fallback) {
    const auto it = extensions.find(name);
    if (it == extensions.end() || !it->second.IsObject()) return fallback;
    const tinygltf::Value& value = it->second.Get(key);
    return value.IsNumber() ? value.GetNumberAsDouble() : fallback;
}

/// The first three numbers of `v` clamped to [0, 1]; black when there are fewer.
Rgb clamped_rgb(const std::vector<double>& v) {
    if (v.size() < 3) return {};
    const auto c = [&](size_t i) { return std::clamp(float(v[i]), 0.0f, 1.0f); };
    return {c(0), c(1), c(2)};
}

void warn_ignored_features(const GltfFile& file, const tinygltf::Material& m,
                           const std::string& where) {
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    const std::pair<bool, const char*> features[] = {
        {pbr.baseColorTexture.index >= 0, "base colour textures are ignored"},
        {pbr.metallicRoughnessTexture.index >= 0, "metallic-roughness textures are ignored"},
        {pbr.metallicFactor > 0, "metallic factors are ignored; metals render as Lambertian"},
        {pbr.roughnessFactor < 1,
         "roughness factors are ignored; surfaces are Lambertian or smooth glass"},
        {m.normalTexture.index >= 0, "normal maps are ignored"},
        {m.occlusionTexture.index >= 0, "occlusion maps are ignored"},
        {m.emissiveTexture.index >= 0, "emissive textures are ignored"},
        {m.alphaMode != "OPAQUE", "alpha modes other than OPAQUE are ignored"},
    };
    for (const auto& [used, what] : features)
        if (used) file.warn_once(what, where);
    static const std::set<std::string> supported = {
        "KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_emissive_strength"};
    for (const auto& [name, value] : m.extensions)
        if (!supported.contains(name))
            file.warn_once("material extension " + name + " is ignored", where);
}

MaterialDesc convert_material(const GltfFile& file, const tinygltf::Material& m,
                              const std::string& where) {
    MaterialDesc desc;
    const Rgb base_colour = clamped_rgb(m.pbrMetallicRoughness.baseColorFactor);
    if (extension_number(m.extensions, "KHR_materials_transmission", "transmissionFactor", 0) <=
        0) {
        desc.reflectance = base_colour;
        return desc;
    }
    desc.type = MaterialType::dielectric;
    desc.transmittance = base_colour;
    desc.ior = float(extension_number(m.extensions, "KHR_materials_ior", "ior", 1.5));
    // KHR_materials_ior allows 0 for "infinitely dense", which a smooth dielectric cannot be.
    if (!(desc.ior >= 1)) {
        spdlog::warn("{}: {}: ior {} is not supported, using 1.5", file.path, where, desc.ior);
        desc.ior = 1.5f;
    }
    return desc;
}

Rgb emission_of(const tinygltf::Material& m) {
    const float strength = float(
        extension_number(m.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1));
    return clamped_rgb(m.emissiveFactor) * std::max(strength, 0.0f);
}

/// `name`, or `name#index` (repeated) when SceneDesc already has a material of that name.
std::string unique_material_name(const SceneDesc& desc, const std::string& name, int index) {
    const auto taken = [&](const std::string& candidate) {
        return std::any_of(desc.materials.begin(), desc.materials.end(),
                           [&](const MaterialDesc& m) { return m.name == candidate; });
    };
    const std::string suffix = "#" + std::to_string(index);
    std::string unique = name;
    while (taken(unique)) unique += suffix;
    return unique;
}

/// Adds glTF material `index` (or the default grey for -1) to `desc`.
ImportedMaterial import_material(const GltfFile& file, int index, SceneDesc& desc) {
    if (index >= int(file.model.materials.size()))
        file.fail("material " + std::to_string(index), "material index out of range");
    ImportedMaterial imported{.index = int(desc.materials.size())};
    if (index < 0) {
        desc.materials.push_back({.name = unique_material_name(desc, "(glTF default)", index)});
        return imported;
    }
    const tinygltf::Material& m = file.model.materials[size_t(index)];
    const std::string where = describe("material", size_t(index), m.name);
    warn_ignored_features(file, m, where);
    MaterialDesc material = convert_material(file, m, where);
    material.name = unique_material_name(
        desc, m.name.empty() ? "material " + std::to_string(index) : m.name, index);
    desc.materials.push_back(material);
    imported.emission = emission_of(m);
    imported.two_sided = m.doubleSided;
    return imported;
}

// ---------------------------------------------------------------------------------------------
// Node placements

Vec3 to_vec3(const std::vector<double>& v) { return {float(v[0]), float(v[1]), float(v[2])}; }

Quat normalized_or_identity(Quat q) { return dot(q, q) > 0 ? normalize(q) : Quat{}; }

/// Splits a column-major node matrix into T * R * S. glTF 2.0 §5.25 requires node matrices
/// to be decomposable (no shear), so three column lengths and one rotation say everything.
AnimatedTrs decompose(const std::vector<double>& m) {
    AnimatedTrs trs;
    trs.translation = {float(m[12]), float(m[13]), float(m[14])};
    Vec3 columns[3];
    for (size_t c = 0; c < 3; ++c)
        columns[c] = {float(m[4 * c]), float(m[4 * c + 1]), float(m[4 * c + 2])};
    trs.scale = {length(columns[0]), length(columns[1]), length(columns[2])};
    // A mirroring matrix is a rotation times a negative scale; put the sign on x.
    if (dot(cross(columns[0], columns[1]), columns[2]) < 0) trs.scale.x = -trs.scale.x;
    // A zero scale flattens the basis beyond recovering a rotation; the object is invisible.
    if (trs.scale.x == 0 || trs.scale.y == 0 || trs.scale.z == 0) return trs;
    trs.rotation = Quat::from_basis(columns[0] / trs.scale.x, columns[1] / trs.scale.y,
                                    columns[2] / trs.scale.z);
    return trs;
}

AnimatedTrs node_placement(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) return decompose(node.matrix);
    AnimatedTrs trs;
    if (node.translation.size() == 3) trs.translation = to_vec3(node.translation);
    if (node.rotation.size() == 4)
        trs.rotation = normalized_or_identity({float(node.rotation[0]), float(node.rotation[1]),
                                               float(node.rotation[2]), float(node.rotation[3])});
    if (node.scale.size() == 3) trs.scale = to_vec3(node.scale);
    return trs;
}

// ---------------------------------------------------------------------------------------------
// Animations

Interpolation parse_interpolation(const GltfFile& file, const std::string& name,
                                  const std::string& where) {
    if (name == "LINEAR") return Interpolation::linear;
    if (name == "STEP") return Interpolation::step;
    if (name == "CUBICSPLINE") return Interpolation::cubic_spline;
    file.fail(where, "unknown interpolation \"" + name + "\" (LINEAR, STEP or CUBICSPLINE)");
}

std::vector<float> read_key_times(const GltfFile& file, int accessor, const std::string& where) {
    std::vector<float> times = read_floats(file, accessor, where + ", input");
    if (times.empty()) file.fail(where, "animation sampler has no keys");
    for (size_t i = 1; i < times.size(); ++i)
        if (!(times[i] > times[i - 1]))
            file.fail(where,
                      "input times must be strictly increasing (key " + std::to_string(i) + ")");
    return times;
}

template <class T>
Track<T> make_track(const GltfFile& file, const tinygltf::AnimationSampler& sampler,
                    std::vector<T> values, const std::string& where) {
    Track<T> track;
    track.interpolation = parse_interpolation(file, sampler.interpolation, where);
    track.times = read_key_times(file, sampler.input, where);
    // CUBICSPLINE stores in-tangent, value, out-tangent per key (glTF 2.0 Appendix C).
    const size_t per_key = track.interpolation == Interpolation::cubic_spline ? 3 : 1;
    if (values.size() != per_key * track.times.size())
        file.fail(where, "output has " + std::to_string(values.size()) + " values for " +
                             std::to_string(track.times.size()) + " keys");
    track.values = std::move(values);
    return track;
}

Track<Quat> make_rotation_track(const GltfFile& file, const tinygltf::AnimationSampler& sampler,
                                const std::string& where) {
    Track<Quat> track =
        make_track(file, sampler, read_quats(file, sampler.output, where + ", output"), where);
    // Normalise the values but not the tangents of a cubic spline, which are derivatives.
    const bool cubic = track.interpolation == Interpolation::cubic_spline;
    for (size_t i = 0; i < track.values.size(); ++i)
        if (!cubic || i % 3 == 1) track.values[i] = normalized_or_identity(track.values[i]);
    return track;
}

/// Points the channel's sampler at the node path it targets; false for paths it cannot animate.
bool apply_channel(const GltfFile& file, const tinygltf::AnimationSampler& sampler,
                   const std::string& path, AnimatedTrs& target, const std::string& where) {
    const auto vec3_track = [&] {
        return make_track(file, sampler, read_vec3s(file, sampler.output, where + ", output"),
                          where);
    };
    if (path == "translation") {
        target.translation_track = vec3_track();
    } else if (path == "rotation") {
        target.rotation_track = make_rotation_track(file, sampler, where);
    } else if (path == "scale") {
        target.scale_track = vec3_track();
    } else {
        file.warn_once(path == "weights" ? "morph target weight animations are ignored"
                                         : "animation target path \"" + path + "\" is ignored",
                       where);
        return false;
    }
    return true;
}

/// The end of the animation's longest sampler, in seconds.
float animation_duration_s(const GltfFile& file, const tinygltf::Animation& animation,
                           const std::string& where) {
    float duration_s = 0;
    for (size_t s = 0; s < animation.samplers.size(); ++s) {
        const std::string sampler_where = where + ", sampler " + std::to_string(s);
        duration_s = std::max(
            duration_s, read_key_times(file, animation.samplers[s].input, sampler_where).back());
    }
    return duration_s;
}

/// Attaches every channel of every animation to `placements`, one per node; returns the
/// longest animation's length in seconds.
float apply_animations(const GltfFile& file, std::vector<AnimatedTrs>& placements) {
    float duration_s = 0;
    std::set<std::pair<int, std::string>> animated;
    for (size_t a = 0; a < file.model.animations.size(); ++a) {
        const tinygltf::Animation& animation = file.model.animations[a];
        const std::string where = describe("animation", a, animation.name);
        duration_s = std::max(duration_s, animation_duration_s(file, animation, where));
        for (size_t c = 0; c < animation.channels.size(); ++c) {
            const tinygltf::AnimationChannel& channel = animation.channels[c];
            const std::string channel_where = where + ", channel " + std::to_string(c);
            // A channel without a node targets something an extension defines; none are supported.
            if (channel.target_node < 0) continue;
            if (size_t(channel.target_node) >= placements.size())
                file.fail(channel_where, "target node out of range");
            if (channel.sampler < 0 || size_t(channel.sampler) >= animation.samplers.size())
                file.fail(channel_where, "sampler index out of range");
            const tinygltf::AnimationSampler& sampler = animation.samplers[size_t(channel.sampler)];
            if (!apply_channel(file, sampler, channel.target_path,
                               placements[size_t(channel.target_node)], channel_where))
                continue;
            if (!animated.insert({channel.target_node, channel.target_path}).second)
                spdlog::warn(
                    "{}: {}: node {} {} is animated by several channels; the last one wins",
                    file.path, channel_where, channel.target_node, channel.target_path);
        }
    }
    return duration_s;
}

// ---------------------------------------------------------------------------------------------
// Scene walk

/// The nodes the walk starts from: those of the default scene (or scene 0), or every node
/// that is nobody's child when the file has no scenes.
std::vector<int> root_nodes(const GltfFile& file) {
    const tinygltf::Model& model = file.model;
    if (model.scenes.empty()) {
        std::vector<bool> is_child(model.nodes.size(), false);
        for (const tinygltf::Node& node : model.nodes)
            for (const int child : node.children)
                if (child >= 0 && size_t(child) < is_child.size()) is_child[size_t(child)] = true;
        std::vector<int> roots;
        for (size_t i = 0; i < model.nodes.size(); ++i)
            if (!is_child[i]) roots.push_back(int(i));
        return roots;
    }
    const bool has_default =
        model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size();
    const size_t scene = has_default ? size_t(model.defaultScene) : 0;
    if (model.scenes.size() > 1)
        file.warn_once("only the default scene is loaded; other scenes are ignored",
                       describe("scene", scene, model.scenes[scene].name));
    return model.scenes[scene].nodes;
}

/// Warns about node extensions and says whether the node carries a KHR_lights_punctual light.
bool has_light(const GltfFile& file, const tinygltf::Node& node, const std::string& where) {
    bool light = false;
    for (const auto& [name, value] : node.extensions) {
        if (name != "KHR_lights_punctual")
            file.warn_once("node extension " + name + " is ignored", where);
        else light = value.IsObject();
    }
    return light;
}

/// Walks the node hierarchy depth first, parents before children, turning each node's mesh
/// primitives, camera and light into SceneDesc entries that share the node's placement chain.
class SceneWalker {
public:
    SceneWalker(const GltfFile& file, const std::vector<AnimatedTrs>& placements, SceneDesc& desc,
                bool& has_camera)
        : m_file(file), m_placements(placements), m_desc(desc), m_has_camera(has_camera) {}

    void visit(int node_index, std::vector<AnimatedTrs>& chain);

private:
    void add_mesh(const tinygltf::Node& node, int node_index,
                  const std::vector<AnimatedTrs>& chain);
    void add_camera(const tinygltf::Node& node, const std::vector<AnimatedTrs>& chain,
                    const std::string& where);
    void add_light(const tinygltf::Node& node, const std::vector<AnimatedTrs>& chain,
                   const std::string& where);
    const ImportedMaterial& material(int gltf_index);

    const GltfFile& m_file;
    const std::vector<AnimatedTrs>& m_placements;
    SceneDesc& m_desc;
    bool& m_has_camera;
    std::map<int, ImportedMaterial> m_materials;  // by glTF index; -1 is the default grey
};

void SceneWalker::visit(int node_index, std::vector<AnimatedTrs>& chain) {
    const tinygltf::Model& model = m_file.model;
    if (node_index < 0 || size_t(node_index) >= model.nodes.size())
        m_file.fail("node " + std::to_string(node_index), "node index out of range");
    const tinygltf::Node& node = model.nodes[size_t(node_index)];
    const std::string where = describe("node", size_t(node_index), node.name);
    if (chain.size() >= model.nodes.size()) m_file.fail(where, "the node hierarchy has a cycle");
    chain.push_back(m_placements[size_t(node_index)]);
    if (node.skin >= 0)
        m_file.warn_once("skins are ignored; skinned meshes keep their node placement", where);
    if (node.mesh >= 0) add_mesh(node, node_index, chain);
    if (node.camera >= 0) add_camera(node, chain, where);
    if (has_light(m_file, node, where)) add_light(node, chain, where);
    for (const int child : node.children) visit(child, chain);
    chain.pop_back();
}

void SceneWalker::add_mesh(const tinygltf::Node& node, int node_index,
                           const std::vector<AnimatedTrs>& chain) {
    if (size_t(node.mesh) >= m_file.model.meshes.size())
        m_file.fail(describe("node", size_t(node_index), node.name), "mesh index out of range");
    const tinygltf::Mesh& mesh = m_file.model.meshes[size_t(node.mesh)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        const tinygltf::Primitive& primitive = mesh.primitives[p];
        const std::string where =
            describe("mesh", size_t(node.mesh), mesh.name) + ", primitive " + std::to_string(p);
        std::optional<TriangleMesh> triangles = read_primitive(m_file, primitive, where);
        if (!triangles) continue;
        const ImportedMaterial& imported = material(primitive.material);
        ObjectDesc object{.name = object_name(node, mesh, node_index, p),
                          .geometry = std::move(*triangles),
                          .material = imported.index,
                          .placement = chain};
        if (!is_black(imported.emission)) {
            object.emission = imported.emission;
            object.two_sided_emission = imported.two_sided;
        }
        m_desc.objects.push_back(std::move(object));
    }
}

const ImportedMaterial& SceneWalker::material(int gltf_index) {
    const int key = std::max(gltf_index, -1);
    auto it = m_materials.find(key);
    if (it == m_materials.end())
        it = m_materials.emplace(key, import_material(m_file, key, m_desc)).first;
    return it->second;
}

void SceneWalker::add_camera(const tinygltf::Node& node, const std::vector<AnimatedTrs>& chain,
                             const std::string& where) {
    if (size_t(node.camera) >= m_file.model.cameras.size())
        m_file.fail(where, "camera index out of range");
    const tinygltf::Camera& camera = m_file.model.cameras[size_t(node.camera)];
    if (camera.type != "perspective") {
        m_file.warn_once(camera.type + " cameras are ignored", where);
        return;
    }
    if (m_has_camera) return;
    const tinygltf::PerspectiveCamera& perspective = camera.perspective;
    if (!(perspective.yfov > 0 && perspective.yfov < pi))
        m_file.fail(where, "camera yfov must lie in (0, pi)");
    CameraDesc& desc = m_desc.camera;
    desc.placement = chain;
    desc.fov_y_deg = float(perspective.yfov) * deg_per_rad;
    const double aspect = perspective.aspectRatio;
    if (aspect > 0 && std::abs(double(desc.width) / desc.height - aspect) > 1e-3 * aspect)
        desc.height = std::max(1, int(std::lround(desc.width / aspect)));
    m_has_camera = true;
}

void SceneWalker::add_light(const tinygltf::Node& node, const std::vector<AnimatedTrs>& chain,
                            const std::string& where) {
    const tinygltf::Value& index = node.extensions.at("KHR_lights_punctual").Get("light");
    const int light_index = index.IsNumber() ? index.GetNumberAsInt() : -1;
    if (light_index < 0 || size_t(light_index) >= m_file.model.lights.size())
        m_file.fail(where, "KHR_lights_punctual light index out of range");
    const tinygltf::Light& light = m_file.model.lights[size_t(light_index)];
    if (light.type != "point" && light.type != "spot") {
        m_file.warn_once(light.type + " lights are ignored", where);
        return;
    }
    if (is_chain_animated(chain))
        m_file.warn_once("animated lights stay where they are at time 0", where);
    const Transform world_from_light = evaluate_chain(chain, 0);
    PointLightDesc desc{
        .name = !light.name.empty() ? light.name : "light " + std::to_string(light_index),
        .type = light.type == "spot" ? PointLightType::spot : PointLightType::point,
        .position = world_from_light.point({}),
        .direction = normalize(world_from_light.vector({0, 0, -1})),
        // Candela taken as W/sr: steadylight has no photometric units.
        .intensity = (light.color.empty() ? Rgb{1, 1, 1} : clamped_rgb(light.color)) *
                     float(std::max(light.intensity, 0.0))};
    if (desc.type == PointLightType::spot) {
        desc.cone_angle_deg =
            std::clamp(float(light.spot.outerConeAngle) * deg_per_rad, 0.01f, 90.0f);
        desc.falloff_start_deg =
            std::clamp(float(light.spot.innerConeAngle) * deg_per_rad, 0.0f, desc.cone_angle_deg);
    }
    m_desc.point_lights.push_back(desc);
}

void warn_required_extensions(const GltfFile& file) {
    static const std::set<std::string> supported = {
        "KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_emissive_strength",
        "KHR_lights_punctual"};
    for (const std::string& name : file.model.extensionsRequired)
        if (!supported.contains(name))
            file.warn_once(
                "required extension " + name + " is not supported; the scene may load wrongly", "");
}

}  // namespace

float append_gltf(const std::string& path, SceneDesc& desc, bool& has_camera) {
    const GltfFile file{.path = path, .model = load_model(path)};
    warn_required_extensions(file);

    // Attach the animation tracks to the nodes first: the walk copies placements into chains.
    std::vector<AnimatedTrs> placements;
    for (const tinygltf::Node& node : file.model.nodes) placements.push_back(node_placement(node));
    const float duration_s = apply_animations(file, placements);

    SceneWalker walker(file, placements, desc, has_camera);
    std::vector<AnimatedTrs> chain;
    for (const int root : root_nodes(file)) walker.visit(root, chain);
    return duration_s;
}

}  // namespace steadylight
