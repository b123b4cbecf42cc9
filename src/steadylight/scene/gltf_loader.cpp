// glTF 2.0 import (gltf_loader.h) in three phases: every node's local placement, then the
// animations that attach tracks to those placements, then a walk of the default scene that
// copies each node's placement chain into its objects, the camera and the lights. Accessors
// (gltf_accessors.cpp), materials (gltf_materials.cpp) and animations (gltf_animation.cpp) live
// in their own files; this one reads the file, the meshes and walks the scene.
// Spec: https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html
#include "steadylight/scene/gltf_loader.h"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <filesystem>
#include <map>
#include <numeric>
#include <optional>
#include <set>

#include <fmt/format.h>

#include "steadylight/base/input_file.h"
#include "steadylight/scene/gltf_accessors.h"
#include "steadylight/scene/gltf_animation.h"
#include "steadylight/scene/gltf_materials.h"
#include "steadylight/scene/image_decoding.h"
#include "steadylight/scene/shapes.h"

namespace steadylight {
namespace {

using namespace gltf;

constexpr float deg_per_rad = 180 / pi;
// KHR_lights_punctual gives candela (lm/sr); steadylight wants W/sr. 683 lm/W is the luminous
// efficacy the SI defines at 540 THz, and the factor Blender's exporter multiplies its watts by
// in its default "Standard" lighting mode (PBR_WATTS_TO_LUMENS), so a Blender point light of
// P watts comes back as P / 4pi W/sr, as Blender renders it.
constexpr double lumens_per_watt = 683;

// ---------------------------------------------------------------------------------------------
// Reading the file

std::string lowercase_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

std::string trim_newlines(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    return s;
}

/// tinygltf's image callback: decodes an embedded or external image (tinygltf reads the bytes,
/// from the buffer view, the data URI or the file beside the glTF) into 8-bit RGBA. An image that
/// is not PNG or JPEG (KTX2, WebP, a broken file) stays empty: textures using it are ignored, with
/// a warning (gltf_materials.cpp). One too large to decode fails the load, as does one whose
/// bufferView runs past its buffer: tinygltf checks the view's and the buffer's indices but not
/// the range it hands over (found by fuzzing). `model` is the model being loaded.
bool decode_gltf_image(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                       const unsigned char* bytes, int size, void* model) {
    if (image->bufferView >= 0) {
        const tinygltf::Model& loading = *static_cast<const tinygltf::Model*>(model);
        const tinygltf::BufferView& view = loading.bufferViews.at(size_t(image->bufferView));
        const size_t buffer_size = loading.buffers.at(size_t(view.buffer)).data.size();
        if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset) {
            if (err)
                *err += fmt::format("image {} \"{}\": bufferView {} runs past the end of buffer {}\n", index,
                                    image->name, image->bufferView, view.buffer);
            return false;
        }
    }
    DecodedImage decoded = decode_image(bytes, size > 0 ? size_t(size) : 0);
    if (decoded.too_large) {
        if (err) *err += fmt::format("image {} \"{}\": {}\n", index, image->uri, decoded.problem);
        return false;
    }
    image->width = decoded.width;
    image->height = decoded.height;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image = std::move(decoded.rgba);
    return true;
}

/// tinygltf's file callbacks: external buffers and images are read as every input file is
/// (base/input_file.h: regular files only), and nothing is ever written.
tinygltf::FsCallbacks input_file_callbacks(const InputFolder& inputs) {
    tinygltf::FsCallbacks callbacks{};
    callbacks.FileExists = [](const std::string& path, void*) {
        struct stat status {};
        return ::stat(path.c_str(), &status) == 0;
    };
    callbacks.ExpandFilePath = [](const std::string& path, void*) { return path; };
    callbacks.ReadWholeFile = [](std::vector<unsigned char>* out, std::string* err, const std::string& path,
                                 void* folder) {
        try {
            const std::string bytes = read_input_file(path, *static_cast<const InputFolder*>(folder));
            out->assign(bytes.begin(), bytes.end());
            return true;
        } catch (const InputError& e) {
            if (err) *err += std::string(e.what()) + "\n";
            return false;
        }
    };
    callbacks.WriteWholeFile = [](std::string*, const std::string&, const std::vector<unsigned char>&, void*) {
        return false;
    };
    callbacks.user_data = const_cast<InputFolder*>(&inputs);  // read only
    return callbacks;
}

tinygltf::Model load_model(const std::string& path, const InputFolder& inputs) {
    const std::string ext = lowercase_extension(path);
    if (ext != ".gltf" && ext != ".glb")
        throw InputError(path, "unknown glTF file extension \"" + ext + "\" (expected .gltf or .glb)");
    const std::string bytes = read_input_file(path, inputs);
    const std::string base_dir = std::filesystem::path(path).parent_path().string();
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    loader.SetImageLoader(decode_gltf_image, &model);
    loader.SetFsCallbacks(input_file_callbacks(inputs));
    std::string err, warn;
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const bool ok =
        ext == ".glb" ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, unsigned(bytes.size()), base_dir)
                      : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), base_dir);
    if (!warn.empty()) spdlog::warn("{}: {}", path, trim_newlines(warn));
    if (!ok) throw InputError(path, err.empty() ? "cannot read the glTF file" : trim_newlines(err));
    return model;
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
        else if (i % 2 == 0)
            triangles.insert(triangles.end(), {v[i], v[i + 1], v[i + 2]});
        else
            triangles.insert(triangles.end(), {v[i], v[i + 2], v[i + 1]});
    }
    return triangles;
}

/// Reads the optional per-vertex attribute `name` with `read`, checking its count.
template <class Read>
auto read_vertex_attribute(const GltfFile& file, const tinygltf::Primitive& primitive, const std::string& name,
                           const std::string& where, size_t vertex_count, Read read) {
    decltype(read(0, std::string())) values;
    const auto it = primitive.attributes.find(name);
    if (it == primitive.attributes.end()) return values;
    values = read(it->second, where + ", " + name);
    if (values.size() != vertex_count) file.fail(where, name + " and POSITION counts differ");
    return values;
}

/// TEXCOORD_0 and _1, COLOR_0 and TANGENT, where the primitive has them.
void read_surface_attributes(const GltfFile& file, const tinygltf::Primitive& primitive, const std::string& where,
                             TriangleMesh& mesh) {
    const size_t n = mesh.positions.size();
    const auto texcoords = [&](int index, const std::string& user) { return read_texcoords(file, index, user); };
    mesh.uv0 = read_vertex_attribute(file, primitive, "TEXCOORD_0", where, n, texcoords);
    mesh.uv1 = read_vertex_attribute(file, primitive, "TEXCOORD_1", where, n, texcoords);
    mesh.colors = read_vertex_attribute(file, primitive, "COLOR_0", where, n, [&](int index, const std::string& user) {
        return read_vec4s(file, index, user, 1);
    });
    mesh.tangents =
        read_vertex_attribute(file, primitive, "TANGENT", where, n,
                              [&](int index, const std::string& user) { return read_vec4s(file, index, user, 1); });
}

void warn_ignored_attributes(const GltfFile& file, const tinygltf::Primitive& primitive, const std::string& where) {
    if (!primitive.targets.empty()) file.warn_once("morph targets are ignored", where);
}

/// The primitive's vertices in drawing order: its indices, or 0, 1, 2, ... without them.
std::vector<int> primitive_vertices(const GltfFile& file, const tinygltf::Primitive& primitive,
                                    const std::string& where, size_t vertex_count) {
    if (primitive.indices >= 0) return read_indices(file, primitive.indices, where + ", indices", vertex_count);
    std::vector<int> vertices(vertex_count);
    std::iota(vertices.begin(), vertices.end(), 0);
    return vertices;
}

/// The primitive's triangles, or nothing for points, lines and primitives without positions.
std::optional<TriangleMesh> read_primitive(const GltfFile& file, const tinygltf::Primitive& primitive,
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
    if (const auto normal = primitive.attributes.find("NORMAL"); normal != primitive.attributes.end()) {
        mesh.normals = read_vec3s(file, normal->second, where + ", NORMAL");
        if (mesh.normals.size() != mesh.positions.size()) file.fail(where, "NORMAL and POSITION counts differ");
    }
    read_surface_attributes(file, primitive, where, mesh);
    mesh.indices = triangulate(primitive_vertices(file, primitive, where, mesh.positions.size()), mode);
    if (mesh.indices.size() % 3 != 0)
        file.fail(where, "triangle vertex count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
    return mesh;
}

std::string object_name(const tinygltf::Node& node, const tinygltf::Mesh& mesh, int node_index, size_t primitive) {
    std::string name = !node.name.empty()   ? node.name
                       : !mesh.name.empty() ? mesh.name
                                            : "node " + std::to_string(node_index);
    // fmt rather than "#" + std::to_string(): GCC 12 warns falsely (-Wrestrict, GCC bug 105329).
    if (mesh.primitives.size() > 1) name += fmt::format("#{}", primitive);
    return name;
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
    const bool has_default = model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size();
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
        else
            light = value.IsObject();
    }
    return light;
}

/// Walks the node hierarchy depth first, parents before children, turning each node's mesh
/// primitives, camera and light into SceneDesc entries that share the node's placement chain.
class SceneWalker {
public:
    SceneWalker(const GltfFile& file, const std::vector<AnimatedTrs>& placements, SceneDesc& desc, bool& has_camera)
        : m_file(file), m_placements(placements), m_desc(desc), m_has_camera(has_camera) {}

    void visit(int node_index, std::vector<AnimatedTrs>& chain);

private:
    void add_mesh(const tinygltf::Node& node, int node_index, const std::vector<AnimatedTrs>& chain);
    void add_camera(const tinygltf::Node& node, const std::vector<AnimatedTrs>& chain, const std::string& where);
    void add_light(const tinygltf::Node& node, const std::vector<AnimatedTrs>& chain, const std::string& where);
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
    if (node.skin >= 0) m_file.warn_once("skins are ignored; skinned meshes keep their node placement", where);
    if (node.mesh >= 0) add_mesh(node, node_index, chain);
    if (node.camera >= 0) add_camera(node, chain, where);
    if (has_light(m_file, node, where)) add_light(node, chain, where);
    for (const int child : node.children) visit(child, chain);
    chain.pop_back();
}

void SceneWalker::add_mesh(const tinygltf::Node& node, int node_index, const std::vector<AnimatedTrs>& chain) {
    if (size_t(node.mesh) >= m_file.model.meshes.size())
        m_file.fail(describe("node", size_t(node_index), node.name), "mesh index out of range");
    const tinygltf::Mesh& mesh = m_file.model.meshes[size_t(node.mesh)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        const tinygltf::Primitive& primitive = mesh.primitives[p];
        const std::string where = describe("mesh", size_t(node.mesh), mesh.name) + ", primitive " + std::to_string(p);
        std::optional<TriangleMesh> triangles = read_primitive(m_file, primitive, where);
        if (!triangles) continue;
        const ImportedMaterial& imported = material(primitive.material);
        const MaterialDesc& used = m_desc.materials[size_t(imported.index)];
        // glTF §3.7.2.1: without TANGENT, a normal-mapped primitive gets generated tangents.
        if (used.normal_texture.is_set() && triangles->tangents.empty())
            generate_tangents(*triangles, used.normal_texture.texcoord);
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
    if (it == m_materials.end()) it = m_materials.emplace(key, import_material(m_file, key, m_desc)).first;
    return it->second;
}

void SceneWalker::add_camera(const tinygltf::Node& node, const std::vector<AnimatedTrs>& chain,
                             const std::string& where) {
    if (size_t(node.camera) >= m_file.model.cameras.size()) m_file.fail(where, "camera index out of range");
    const tinygltf::Camera& camera = m_file.model.cameras[size_t(node.camera)];
    if (camera.type != "perspective") {
        m_file.warn_once(camera.type + " cameras are ignored", where);
        return;
    }
    if (m_has_camera) return;
    const tinygltf::PerspectiveCamera& perspective = camera.perspective;
    if (!(perspective.yfov > 0 && perspective.yfov < pi)) m_file.fail(where, "camera yfov must lie in (0, pi)");
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
    if (light.type != "point" && light.type != "spot" && light.type != "directional") {
        m_file.warn_once(light.type + " lights are ignored", where);
        return;
    }
    // A light sits at its node's origin and shines down the node's -z; the node and its
    // ancestors place it in the world, and move it where they are animated.
    const Rgb color = light.color.empty() ? Rgb{1, 1, 1} : clamped_rgb(light.color);
    if (light.type == "directional") {
        // Illuminance in lux; Blender writes W/m² × 683 (docs/gltf.md). glTF has no sun angle:
        // the real sun's, unless a wrapper JSON sets it by the node's name.
        m_desc.suns.push_back({.name = !node.name.empty() ? node.name : "sun " + std::to_string(light_index),
                               .direction = {0, 0, -1},
                               .irradiance = color * float(std::max(light.intensity, 0.0) / lumens_per_watt),
                               .placement = chain});
        return;
    }
    PointLightDesc desc{.name = !light.name.empty() ? light.name : "light " + std::to_string(light_index),
                        .type = light.type == "spot" ? PointLightType::spot : PointLightType::point,
                        .position = {},
                        .direction = {0, 0, -1},
                        .intensity = color * float(std::max(light.intensity, 0.0) / lumens_per_watt),
                        .placement = chain};
    if (desc.type == PointLightType::spot) {
        desc.cone_angle_deg = std::clamp(float(light.spot.outerConeAngle) * deg_per_rad, 0.01f, 90.0f);
        desc.falloff_start_deg = std::clamp(float(light.spot.innerConeAngle) * deg_per_rad, 0.0f, desc.cone_angle_deg);
    }
    m_desc.point_lights.push_back(desc);
}

/// A URI with its %XX escapes decoded (glTF URIs are RFC 3986; "my%20wood.png").
std::string decode_uri(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(uint8_t(uri[i + 1])) &&
            std::isxdigit(uint8_t(uri[i + 2]))) {
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

/// Every image of the file, in file order from `file.image_base` on; one that could not be
/// decoded as a white texel, which no texture uses (gltf_materials.cpp ignores those textures).
void append_images(const GltfFile& file, SceneDesc& desc) {
    for (size_t i = 0; i < file.model.images.size(); ++i) {
        const tinygltf::Image& image = file.model.images[i];
        const std::string name = image.name.empty() ? image.uri : image.name;
        // tinygltf only warns about a missing image file; it is an error, as a missing buffer is.
        if (!image.uri.empty() && !image.uri.starts_with("data:") &&
            !std::filesystem::exists(std::filesystem::path(file.path).parent_path() / decode_uri(image.uri)))
            file.fail(describe("image", i, image.name), "image file \"" + image.uri + "\" not found");
        if (!is_decoded(image)) {
            desc.images.push_back({.name = name, .width = 1, .height = 1, .rgba = {255, 255, 255, 255}});
            continue;
        }
        desc.images.push_back({.name = name, .width = image.width, .height = image.height, .rgba = image.image});
    }
}

void warn_required_extensions(const GltfFile& file) {
    static const std::set<std::string> supported = {"KHR_materials_transmission",      "KHR_materials_ior",
                                                    "KHR_materials_emissive_strength", "KHR_lights_punctual",
                                                    "KHR_texture_transform",           "KHR_materials_specular"};
    for (const std::string& name : file.model.extensionsRequired)
        if (!supported.contains(name))
            file.warn_once("required extension " + name + " is not supported; the scene may load wrongly", "");
}

}  // namespace

bool is_gltf_file(const std::string& path) {
    const std::string ext = lowercase_extension(path);
    return ext == ".gltf" || ext == ".glb";
}

int frames_covering(float duration_s, float fps) {
    const double frames = 1 + std::floor(double(duration_s) * double(fps) + 1e-3);
    return frames < double(INT_MAX) ? int(frames) : INT_MAX;  // validate() says when it is too many
}

SceneDesc load_gltf_scene_desc(const std::string& path, bool confine_inputs) {
    SceneDesc desc;
    desc.source_file = path;
    desc.name = std::filesystem::path(path).stem().string();
    check_scene_name(desc.name, path);
    bool has_camera = false;
    const float duration_s =
        append_gltf(path, desc, has_camera, confine_inputs ? InputFolder::of_scene(path) : InputFolder{});
    if (!has_camera)
        throw InputError(
            path,
            "the file has no perspective camera (add one, or include the file from a JSON scene with a \"camera\")");
    desc.frame_count = frames_covering(duration_s, desc.fps);
    validate(desc);
    return desc;
}

float append_gltf(const std::string& path, SceneDesc& desc, bool& has_camera, const InputFolder& inputs) {
    const GltfFile file{.path = path, .model = load_model(path, inputs), .image_base = int(desc.images.size())};
    append_images(file, desc);
    warn_required_extensions(file);

    // Attach the animation tracks to the nodes first: the walk copies placements into chains.
    std::vector<AnimatedTrs> placements;
    for (const tinygltf::Node& node : file.model.nodes) placements.push_back(node_placement(node));
    const float duration_s = apply_animations(file, placements);
    if (const std::optional<float> rate = sampled_frame_rate(file)) {
        spdlog::info("{}: animation keys are one every 1/{:.6g} s; using {:.6g} fps as the frame rate", path, *rate,
                     *rate);
        desc.fps = *rate;
        desc.fps_source = FpsSource::gltf_keys;
    }

    SceneWalker walker(file, placements, desc, has_camera);
    std::vector<AnimatedTrs> chain;
    for (const int root : root_nodes(file)) walker.visit(root, chain);
    return duration_s;
}

}  // namespace steadylight
