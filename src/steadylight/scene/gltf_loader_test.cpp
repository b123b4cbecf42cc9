// Tests for the glTF importer (gltf_loader.h). Each test builds a tinygltf::Model in code, writes
// it with tinygltf as .gltf and as .glb into a temporary directory, and checks what append_gltf
// makes of both files.
#include "steadylight/scene/gltf_loader.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "steadylight/base/error.h"
#include "support/input_error.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Building models

/// Appends `size` bytes to buffer 0 as a new bufferView and returns an accessor over them.
int add_accessor(tinygltf::Model& model, const void* bytes, size_t size, int component_type, int type, size_t count) {
    if (model.buffers.empty()) model.buffers.emplace_back();
    std::vector<unsigned char>& data = model.buffers[0].data;
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = size;
    const auto* first = static_cast<const unsigned char*>(bytes);
    data.insert(data.end(), first, first + size);
    data.resize((data.size() + 3) / 4 * 4);  // glTF wants every view 4-byte aligned
    model.bufferViews.push_back(view);
    tinygltf::Accessor accessor;
    accessor.bufferView = int(model.bufferViews.size()) - 1;
    accessor.componentType = component_type;
    accessor.type = type;
    accessor.count = count;
    model.accessors.push_back(accessor);
    return int(model.accessors.size()) - 1;
}

int add_floats(tinygltf::Model& model, const std::vector<float>& values, int type) {
    const size_t components = size_t(tinygltf::GetNumComponentsInType(uint32_t(type)));
    return add_accessor(model, values.data(), values.size() * sizeof(float), TINYGLTF_COMPONENT_TYPE_FLOAT, type,
                        values.size() / components);
}

/// A primitive over `positions` (x, y, z each), drawn without indices.
tinygltf::Primitive make_primitive(tinygltf::Model& model, const std::vector<float>& positions,
                                   int mode = TINYGLTF_MODE_TRIANGLES, int material = -1) {
    tinygltf::Primitive primitive;
    primitive.attributes["POSITION"] = add_floats(model, positions, TINYGLTF_TYPE_VEC3);
    primitive.mode = mode;
    primitive.material = material;
    return primitive;
}

/// A mesh of one indexed triangle (0,0,0), (1,0,0), (0,1,0) facing +z.
int add_triangle_mesh(tinygltf::Model& model, int material = -1) {
    tinygltf::Primitive primitive =
        make_primitive(model, {0, 0, 0, 1, 0, 0, 0, 1, 0}, TINYGLTF_MODE_TRIANGLES, material);
    const uint16_t indices[] = {0, 1, 2};
    primitive.indices =
        add_accessor(model, indices, sizeof indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, 3);
    tinygltf::Mesh mesh;
    mesh.primitives.push_back(primitive);
    model.meshes.push_back(mesh);
    return int(model.meshes.size()) - 1;
}

tinygltf::Node make_node(const std::string& name, int mesh = -1, std::vector<double> translation = {}) {
    tinygltf::Node node;
    node.name = name;
    node.mesh = mesh;
    node.translation = std::move(translation);
    return node;
}

/// Adds `node` under `parent`, or as a root of scene 0 when `parent` is -1.
int add_node(tinygltf::Model& model, tinygltf::Node node, int parent = -1) {
    const int index = int(model.nodes.size());
    model.nodes.push_back(std::move(node));
    if (model.scenes.empty()) model.scenes.emplace_back();
    if (parent >= 0)
        model.nodes[size_t(parent)].children.push_back(index);
    else
        model.scenes[0].nodes.push_back(index);
    return index;
}

tinygltf::Material make_material(const std::string& name, std::vector<double> base_colour) {
    tinygltf::Material material;
    material.name = name;
    material.emissiveFactor = {0, 0, 0};  // tinygltf writes an invalid [] when left empty
    material.pbrMetallicRoughness.baseColorFactor = std::move(base_colour);
    material.pbrMetallicRoughness.baseColorFactor.push_back(1);  // alpha
    material.pbrMetallicRoughness.metallicFactor = 0;
    return material;
}

/// A JSON object {key: number}, as extensions hold them.
tinygltf::Value number_object(const std::string& key, double number) {
    return tinygltf::Value(tinygltf::Value::Object{{key, tinygltf::Value(number)}});
}

/// A model of one triangle on a root node that uses `material`.
tinygltf::Model triangle_with_material(const tinygltf::Material& material) {
    tinygltf::Model model;
    model.materials.push_back(material);
    add_node(model, make_node("Tri", add_triangle_mesh(model, 0)));
    return model;
}

/// Adds an animation with one channel that drives `path` of `node` from `values` (VEC4 for
/// rotations, VEC3 otherwise) at `times`.
void add_animation(tinygltf::Model& model, int node, const std::string& path, const std::string& interpolation,
                   const std::vector<float>& times, const std::vector<float>& values) {
    tinygltf::AnimationSampler sampler;
    sampler.input = add_floats(model, times, TINYGLTF_TYPE_SCALAR);
    sampler.output = add_floats(model, values, path == "rotation" ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3);
    sampler.interpolation = interpolation;
    tinygltf::AnimationChannel channel;
    channel.sampler = 0;
    channel.target_node = node;
    channel.target_path = path;
    tinygltf::Animation animation;
    animation.samplers.push_back(sampler);
    animation.channels.push_back(channel);
    model.animations.push_back(animation);
}

// ---------------------------------------------------------------------------------------------
// Loading and checking

struct Loaded {
    std::string path;
    SceneDesc desc;
    bool has_camera = false;
    float duration_s = 0;
};

Loaded load(const std::string& path) {
    Loaded loaded{.path = path};
    loaded.duration_s = append_gltf(path, loaded.desc, loaded.has_camera);
    return loaded;
}

/// Expects loading `path` to throw an InputError that names the file and says `what`.
void expect_input_error(const std::string& path, const std::string& what) {
    SCOPED_TRACE(path);
    SceneDesc desc;
    bool has_camera = false;
    try {
        append_gltf(path, desc, has_camera);
        ADD_FAILURE() << "loaded without an error";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(fs::path(path).filename().string()), std::string::npos) << message;
        EXPECT_NE(message.find(what), std::string::npos) << message;
    }
}

const ObjectDesc& find_object(const SceneDesc& desc, const std::string& name) {
    for (const ObjectDesc& object : desc.objects)
        if (object.name == name) return object;
    throw std::runtime_error("no object \"" + name + "\"");
}

const TriangleMesh& mesh_of(const ObjectDesc& object) { return std::get<TriangleMesh>(object.geometry); }

/// Where vertex `v` of `object` is in the world at `time_s`.
Vec3 world_vertex(const ObjectDesc& object, size_t v, float time_s) {
    return evaluate_chain(object.placement, time_s).point(mesh_of(object).positions[v]);
}

void expect_near(Vec3 actual, Vec3 expected, float tolerance = 1e-5f) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

void expect_near(Rgb actual, Rgb expected) {
    expect_near(Vec3{actual.r, actual.g, actual.b}, Vec3{expected.r, expected.g, expected.b});
}

/// Each test gets a fresh temporary directory for the files it writes.
class GltfLoader : public ::testing::Test {
protected:
    void SetUp() override {
        const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
        m_dir = fs::temp_directory_path() / ("steadylight_gltf_" + test + "_" + std::to_string(std::random_device{}()));
        fs::create_directories(m_dir);
    }
    void TearDown() override { fs::remove_all(m_dir); }

    /// Writes `model` as `name` (.gltf or .glb, buffers embedded) and returns the path.
    std::string write(const tinygltf::Model& model, const std::string& name) const {
        const std::string path = (m_dir / name).string();
        const bool binary = fs::path(name).extension() == ".glb";
        tinygltf::TinyGLTF writer;
        EXPECT_TRUE(writer.WriteGltfSceneToFile(&model, path, false, true, true, binary));
        return path;
    }

    /// The paths of `model` written as model.gltf and as model.glb.
    std::vector<std::string> write_both(const tinygltf::Model& model) const {
        return {write(model, "model.gltf"), write(model, "model.glb")};
    }

    /// `model` written in both formats and loaded from each into a fresh SceneDesc.
    std::vector<Loaded> write_and_load(const tinygltf::Model& model) const {
        std::vector<Loaded> loaded;
        for (const std::string& path : write_both(model)) loaded.push_back(load(path));
        return loaded;
    }

    fs::path m_dir;
};

// ---------------------------------------------------------------------------------------------
// Geometry and hierarchy

TEST_F(GltfLoader, TriangleUnderTranslatedScaledParentLandsAtItsWorldPosition) {
    tinygltf::Model model;
    tinygltf::Node parent = make_node("Parent", -1, {1, 2, 3});
    parent.scale = {2, 2, 2};
    const int parent_index = add_node(model, parent);
    add_node(model, make_node("Tri", add_triangle_mesh(model), {0, 0, -1}), parent_index);
    model.meshes[0].primitives[0].attributes["NORMAL"] =
        add_floats(model, {0, 0, 1, 0, 0, 1, 0, 0, 1}, TINYGLTF_TYPE_VEC3);
    for (const Loaded& loaded : write_and_load(model)) {
        SCOPED_TRACE(loaded.path);
        ASSERT_EQ(loaded.desc.objects.size(), 1u);
        const ObjectDesc& tri = find_object(loaded.desc, "Tri");
        EXPECT_EQ(tri.placement.size(), 2u);
        EXPECT_EQ(mesh_of(tri).indices, (std::vector<int>{0, 1, 2}));
        ASSERT_EQ(mesh_of(tri).normals.size(), 3u);
        expect_near(mesh_of(tri).normals[2], {0, 0, 1});
        expect_near(world_vertex(tri, 0, 0), {1, 2, 1});
        expect_near(world_vertex(tri, 1, 0), {3, 2, 1});
        expect_near(world_vertex(tri, 2, 0), {1, 4, 1});
        EXPECT_FALSE(tri.is_dynamic());
        EXPECT_EQ(loaded.duration_s, 0);
    }
}

TEST_F(GltfLoader, NodeMatrixIsDecomposedIntoTranslationRotationScale) {
    // A mirroring scale checks that the decomposition keeps the handedness.
    const Transform expected = Transform::from_trs({1, -2, 3}, Quat::from_axis_angle({1, 1, 0}, 0.5f), {2, -1, 0.5f});
    tinygltf::Node node = make_node("Tri", -1);
    for (int column = 0; column < 4; ++column)
        for (int row = 0; row < 4; ++row)
            node.matrix.push_back(row < 3 ? expected.m[row][column] : (column == 3 ? 1 : 0));
    tinygltf::Model model;
    node.mesh = add_triangle_mesh(model);
    add_node(model, node);
    for (const Loaded& loaded : write_and_load(model)) {
        SCOPED_TRACE(loaded.path);
        const ObjectDesc& tri = find_object(loaded.desc, "Tri");
        for (size_t v = 0; v < 3; ++v) expect_near(world_vertex(tri, v, 0), expected.point(mesh_of(tri).positions[v]));
    }
}

TEST_F(GltfLoader, EachTrianglePrimitiveBecomesAnObjectNamedAfterNodeOrMesh) {
    tinygltf::Model model;
    tinygltf::Mesh pair;
    pair.name = "Pair";
    pair.primitives = {make_primitive(model, {0, 0, 0, 1, 0, 0, 0, 1, 0}),
                       make_primitive(model, {0, 0, 1, 1, 0, 1, 0, 1, 1})};
    model.meshes.push_back(pair);
    add_node(model, make_node("", 0));
    add_node(model, make_node("", add_triangle_mesh(model)));
    for (const Loaded& loaded : write_and_load(model)) {
        SCOPED_TRACE(loaded.path);
        ASSERT_EQ(loaded.desc.objects.size(), 3u);
        EXPECT_EQ(loaded.desc.objects[0].name, "Pair#0");
        EXPECT_EQ(loaded.desc.objects[1].name, "Pair#1");
        EXPECT_EQ(loaded.desc.objects[2].name, "node 1");
    }
}

TEST_F(GltfLoader, StripsAndFansAreTriangulatedAndPointsSkipped) {
    tinygltf::Model model;
    const std::vector<float> quad = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    tinygltf::Mesh mesh;
    mesh.primitives = {make_primitive(model, quad, TINYGLTF_MODE_TRIANGLE_STRIP),
                       make_primitive(model, quad, TINYGLTF_MODE_TRIANGLE_FAN),
                       make_primitive(model, quad, TINYGLTF_MODE_POINTS)};
    model.meshes.push_back(mesh);
    add_node(model, make_node("Quad", 0));
    for (const Loaded& loaded : write_and_load(model)) {
        SCOPED_TRACE(loaded.path);
        ASSERT_EQ(loaded.desc.objects.size(), 2u);
        // glTF 2.0 §3.7.2.1: strip triangle i is (i, i+1, i+2) for even i and (i, i+2, i+1)
        // for odd i; fan triangle i is (i+1, i+2, 0).
        EXPECT_EQ(mesh_of(find_object(loaded.desc, "Quad#0")).indices, (std::vector<int>{0, 1, 2, 1, 3, 2}));
        EXPECT_EQ(mesh_of(find_object(loaded.desc, "Quad#1")).indices, (std::vector<int>{1, 2, 0, 2, 3, 0}));
    }
}

// ---------------------------------------------------------------------------------------------
// Materials

TEST_F(GltfLoader, BaseColourBecomesClampedPbrBaseColour) {
    const tinygltf::Model model = triangle_with_material(make_material("Paint", {0.2, 0.4, 1.5}));
    for (const Loaded& loaded : write_and_load(model)) {
        SCOPED_TRACE(loaded.path);
        ASSERT_EQ(loaded.desc.materials.size(), 1u);
        const MaterialDesc& paint = loaded.desc.materials[0];
        EXPECT_EQ(paint.name, "Paint");
        EXPECT_EQ(paint.type, MaterialType::pbr);
        expect_near(paint.reflectance, {0.2f, 0.4f, 1});
        EXPECT_EQ(paint.metallic, 0.0f);
        EXPECT_EQ(paint.roughness, 1.0f);  // glTF's default
        EXPECT_EQ(paint.alpha_mode, AlphaMode::opaque);
        EXPECT_EQ(loaded.desc.objects[0].material, 0);
        EXPECT_FALSE(loaded.desc.objects[0].is_emitter());
    }
}

TEST_F(GltfLoader, PrimitiveWithoutMaterialGetsDefaultGreyLambert) {
    tinygltf::Model model;
    add_node(model, make_node("Tri", add_triangle_mesh(model)));
    for (const Loaded& loaded : write_and_load(model)) {
        SCOPED_TRACE(loaded.path);
        ASSERT_EQ(loaded.desc.materials.size(), 1u);
        EXPECT_EQ(loaded.desc.materials[0].type, MaterialType::lambert);
        expect_near(loaded.desc.materials[0].reflectance, {0.8f, 0.8f, 0.8f});
    }
}

TEST_F(GltfLoader, MaterialNameAlreadyInTheSceneGetsTheIndexAppended) {
    const std::string path = write(triangle_with_material(make_material("Paint", {1, 1, 1})), "m.glb");
    SceneDesc desc;
    desc.materials.push_back({.name = "Paint"});
    bool has_camera = false;
    append_gltf(path, desc, has_camera);
    ASSERT_EQ(desc.materials.size(), 2u);
    EXPECT_EQ(desc.materials[1].name, "Paint#0");
    EXPECT_EQ(desc.objects[0].material, 1);
}

TEST_F(GltfLoader, EmissiveMaterialBecomesAreaLight) {
    tinygltf::Material material = make_material("Lamp", {0.5, 0.5, 0.5});
    material.emissiveFactor = {1, 0.5, 0.25};
    material.extensions["KHR_materials_emissive_strength"] = number_object("emissiveStrength", 4);
    material.doubleSided = true;
    for (const Loaded& loaded : write_and_load(triangle_with_material(material))) {
        SCOPED_TRACE(loaded.path);
        const ObjectDesc& tri = find_object(loaded.desc, "Tri");
        EXPECT_TRUE(tri.is_emitter());
        expect_near(tri.emission, {4, 2, 1});
        EXPECT_TRUE(tri.two_sided_emission);
        expect_near(loaded.desc.materials[size_t(tri.material)].reflectance, {0.5f, 0.5f, 0.5f});
    }
}

TEST_F(GltfLoader, TransmissionWithIorBecomesDielectric) {
    tinygltf::Material material = make_material("Glass", {0.9, 1, 0.95});
    material.extensions["KHR_materials_transmission"] = number_object("transmissionFactor", 1);
    material.extensions["KHR_materials_ior"] = number_object("ior", 1.33);
    for (const Loaded& loaded : write_and_load(triangle_with_material(material))) {
        SCOPED_TRACE(loaded.path);
        const MaterialDesc& glass = loaded.desc.materials[0];
        EXPECT_EQ(glass.type, MaterialType::dielectric);
        EXPECT_FLOAT_EQ(glass.ior, 1.33f);
        expect_near(glass.transmittance, {0.9f, 1, 0.95f});
    }
}

// KHR_materials_volume: absorption when the thickness says the mesh is a volume; the roughness
// makes rough glass.
TEST_F(GltfLoader, VolumeGivesGlassAbsorptionAndRoughnessMakesItRough) {
    tinygltf::Material material = make_material("Amber", {1, 1, 1});
    material.pbrMetallicRoughness.roughnessFactor = 0.3;
    material.extensions["KHR_materials_transmission"] = number_object("transmissionFactor", 1);
    tinygltf::Value::Object volume{{"thicknessFactor", tinygltf::Value(0.5)},
                                   {"attenuationDistance", tinygltf::Value(0.25)}};
    volume["attenuationColor"] =
        tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(0.9), tinygltf::Value(0.5), tinygltf::Value(0.2)});
    material.extensions["KHR_materials_volume"] = tinygltf::Value(volume);
    for (const Loaded& loaded : write_and_load(triangle_with_material(material))) {
        SCOPED_TRACE(loaded.path);
        const MaterialDesc& glass = loaded.desc.materials[0];
        EXPECT_EQ(glass.type, MaterialType::dielectric);
        EXPECT_FLOAT_EQ(glass.roughness, 0.3f);
        EXPECT_FLOAT_EQ(glass.attenuation_distance, 0.25f);
        expect_near(glass.attenuation_color, {0.9f, 0.5f, 0.2f});
        // Light that crosses 0.25 units keeps the attenuation colour.
        expect_near(glass.absorption() * -0.25f, {std::log(0.9f), std::log(0.5f), std::log(0.2f)});
    }
}

TEST_F(GltfLoader, ThinWalledVolumeAbsorbsNothing) {
    tinygltf::Material material = make_material("Thin", {1, 1, 1});
    material.extensions["KHR_materials_transmission"] = number_object("transmissionFactor", 1);
    material.extensions["KHR_materials_volume"] = number_object("attenuationDistance", 0.25);  // thickness 0
    for (const Loaded& loaded : write_and_load(triangle_with_material(material))) {
        SCOPED_TRACE(loaded.path);
        EXPECT_TRUE(is_black(loaded.desc.materials[0].absorption()));
    }
}

// ---------------------------------------------------------------------------------------------
// Camera and lights

/// A model with one perspective camera (60° vertical, aspect 2) on a node at (0, 1, 5) turned
/// 90° about +y.
tinygltf::Model camera_model() {
    tinygltf::Model model;
    tinygltf::Camera camera;
    camera.type = "perspective";
    camera.perspective.yfov = pi / 3;
    camera.perspective.aspectRatio = 2;
    camera.perspective.znear = 0.1;
    model.cameras.push_back(camera);
    tinygltf::Node node = make_node("Cam", -1, {0, 1, 5});
    node.rotation = {0, std::sin(pi / 4), 0, std::cos(pi / 4)};
    node.camera = 0;
    add_node(model, node);
    return model;
}

TEST_F(GltfLoader, PerspectiveCameraNodeBecomesSceneCamera) {
    for (const Loaded& loaded : write_and_load(camera_model())) {
        SCOPED_TRACE(loaded.path);
        EXPECT_TRUE(loaded.has_camera);
        const CameraDesc& camera = loaded.desc.camera;
        EXPECT_NEAR(camera.fov_y_deg, 60, 1e-4);
        EXPECT_EQ(camera.width, 320);
        EXPECT_EQ(camera.height, 160);
        const Transform world_from_camera = evaluate_chain(camera.placement, 0);
        expect_near(world_from_camera.point({}), {0, 1, 5});
        expect_near(world_from_camera.vector({0, 0, -1}), {-1, 0, 0});  // looks down -x
    }
}

TEST_F(GltfLoader, CameraIsIgnoredWhenTheSceneAlreadyHasOne) {
    SceneDesc desc;
    bool has_camera = true;
    append_gltf(write(camera_model(), "cam.gltf"), desc, has_camera);
    EXPECT_TRUE(desc.camera.placement.empty());
    EXPECT_EQ(desc.camera.height, 240);
}

/// `light` added to `model` on a node named `name` at `position`, turned so that its -z points down.
void add_light_shining_down(tinygltf::Model& model, const tinygltf::Light& light, const std::string& name,
                            std::vector<double> position) {
    model.lights.push_back(light);
    tinygltf::Node node = make_node(name, -1, position);
    node.rotation = {-std::sin(pi / 4), 0, 0, std::cos(pi / 4)};  // -z turned to -y
    node.extensions["KHR_lights_punctual"] = number_object("light", int(model.lights.size()) - 1);
    add_node(model, node);
}

TEST_F(GltfLoader, SpotLightBecomesPointLightDesc) {
    tinygltf::Model model;
    tinygltf::Light light;
    light.type = "spot";
    light.color = {1, 0.5, 0.5};
    light.intensity = 10;
    light.spot.innerConeAngle = pi / 8;
    light.spot.outerConeAngle = pi / 4;
    add_light_shining_down(model, light, "Spot", {0, 3, 0});
    for (const Loaded& loaded : write_and_load(model)) {
        SCOPED_TRACE(loaded.path);
        ASSERT_EQ(loaded.desc.point_lights.size(), 1u);
        const PointLightDesc& spot = loaded.desc.point_lights[0];
        EXPECT_EQ(spot.type, PointLightType::spot);
        EXPECT_FALSE(spot.is_moving());
        expect_near(spot.pose_at(0).position, {0, 3, 0});
        expect_near(spot.pose_at(0).direction, {0, -1, 0});
        expect_near(spot.intensity, Rgb{10, 5, 5} / 683.0f);  // candela to W/sr at 683 lm/W
        EXPECT_NEAR(spot.cone_angle_deg, 45, 1e-4);
        EXPECT_NEAR(spot.falloff_start_deg, 22.5, 1e-4);
    }
}

// A directional light is a sun: down its node's -z, lux / 683 W/m^2 as Blender's exporter writes
// a sun of S W/m^2 (S x 683), 0.53 degrees wide unless a wrapper JSON gives its angle by name.
TEST_F(GltfLoader, DirectionalLightBecomesASunWhoseAngleAWrapperGivesByName) {
    tinygltf::Model model = camera_model();
    tinygltf::Light light;
    light.type = "directional";
    light.color = {1, 0.5, 0.25};
    light.intensity = 683 * 4;
    add_light_shining_down(model, light, "Sun", {0, 10, 0});
    for (const Loaded& loaded : write_and_load(model)) {
        SCOPED_TRACE(loaded.path);
        ASSERT_EQ(loaded.desc.suns.size(), 1u);
        const SunLightDesc& sun = loaded.desc.suns[0];
        EXPECT_EQ(sun.name, "Sun");
        expect_near(sun.direction_at(0), {0, -1, 0});
        expect_near(sun.irradiance, Rgb{4, 2, 1});
        EXPECT_EQ(sun.angle_deg, SunLightDesc::default_sun_angle_deg);
    }
    write(model, "sun.glb");
    const fs::path wrapper = m_dir / "scene.json";
    std::ofstream(wrapper) << R"({"gltf": "sun.glb", "sun_angles_degrees": {"Sun": 2.5}})";
    EXPECT_EQ(load_scene_desc(wrapper.string()).suns.at(0).angle_deg, 2.5f);
    for (const auto& [angles, error] :
         {std::pair{R"({"Moon": 2.5})", "/sun_angles_degrees/Moon: no sun light of that name"},
          std::pair{R"({"Sun": 91})", "/sun_angles_degrees/Sun: must lie in [0, 90]"}}) {
        std::ofstream(wrapper) << R"({"gltf": "sun.glb", "sun_angles_degrees": )" << angles << "}";
        try {
            load_scene_desc(wrapper.string());
            ADD_FAILURE() << angles << " loaded without an error";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(std::string("scene.json:") + error), std::string::npos) << e.what();
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Animation

TEST_F(GltfLoader, LinearTranslationMovesObjectWhileSiblingStaysStatic) {
    tinygltf::Model model;
    const int mesh = add_triangle_mesh(model);
    const int mover = add_node(model, make_node("Mover", mesh));
    add_node(model, make_node("Still", mesh, {0, 5, 0}));
    add_animation(model, mover, "translation", "LINEAR", {0, 2}, {0, 0, 0, 4, 0, 0});
    for (const Loaded& loaded : write_and_load(model)) {
        SCOPED_TRACE(loaded.path);
        EXPECT_FLOAT_EQ(loaded.duration_s, 2);
        const ObjectDesc& moving = find_object(loaded.desc, "Mover");
        EXPECT_TRUE(moving.is_dynamic());
        EXPECT_FALSE(find_object(loaded.desc, "Still").is_dynamic());
        expect_near(world_vertex(moving, 0, 1), {2, 0, 0});
        expect_near(world_vertex(moving, 0, 3), {4, 0, 0});
    }
}

TEST_F(GltfLoader, StepRotationHoldsEachKeyUntilTheNext) {
    tinygltf::Model model;
    const int node = add_node(model, make_node("Turner", add_triangle_mesh(model)));
    const float s = std::sin(pi / 4), c = std::cos(pi / 4);
    add_animation(model, node, "rotation", "STEP", {0, 1}, {0, 0, 0, 1, 0, 0, s, c});
    for (const Loaded& loaded : write_and_load(model)) {
        SCOPED_TRACE(loaded.path);
        const ObjectDesc& turner = find_object(loaded.desc, "Turner");
        EXPECT_EQ(turner.placement[0].rotation_track->interpolation, Interpolation::step);
        expect_near(world_vertex(turner, 1, 0.99f), {1, 0, 0});
        expect_near(world_vertex(turner, 1, 1.01f), {0, 1, 0});
    }
}

// A lamp moves with its node and the node's parents; a sun turns with its node.
TEST_F(GltfLoader, AnimatedLightsMoveWithTheirNodesAndParents) {
    tinygltf::Model model = camera_model();
    const int carrier = add_node(model, make_node("Carrier", -1));
    add_animation(model, carrier, "translation", "LINEAR", {0, 2}, {0, 0, 0, 4, 0, 0});
    tinygltf::Light spot;
    spot.type = "spot";
    spot.intensity = 683;
    model.lights.push_back(spot);
    tinygltf::Node torch = make_node("Torch", -1, {0, 3, 0});
    torch.rotation = {-std::sin(pi / 4), 0, 0, std::cos(pi / 4)};  // -z turned to -y
    torch.extensions["KHR_lights_punctual"] = number_object("light", 0);
    add_node(model, torch, carrier);
    tinygltf::Light sun;
    sun.type = "directional";
    sun.intensity = 683;
    add_light_shining_down(model, sun, "Sun", {0, 10, 0});
    // The sun's node turns in 2 s from shining down to shining along +x.
    const float s = std::sin(pi / 4), c = std::cos(pi / 4);
    add_animation(model, int(model.nodes.size()) - 1, "rotation", "LINEAR", {0, 2}, {-s, 0, 0, c, 0, -s, 0, c});
    for (const Loaded& loaded : write_and_load(model)) {
        SCOPED_TRACE(loaded.path);
        ASSERT_EQ(loaded.desc.point_lights.size(), 1u);
        ASSERT_EQ(loaded.desc.suns.size(), 1u);
        const PointLightDesc& lamp = loaded.desc.point_lights[0];
        EXPECT_TRUE(lamp.is_moving());
        expect_near(lamp.pose_at(0).position, {0, 3, 0});
        expect_near(lamp.pose_at(1).position, {2, 3, 0});
        expect_near(lamp.pose_at(2).direction, {0, -1, 0});
        const SunLightDesc& moving_sun = loaded.desc.suns[0];
        EXPECT_TRUE(moving_sun.is_moving());
        expect_near(moving_sun.direction_at(0), {0, -1, 0});
        expect_near(moving_sun.direction_at(2), {1, 0, 0});
    }
}

// A light carried by a node whose track holds a NaN is refused, naming the file and the light.
TEST_F(GltfLoader, LightMovedByANonFiniteTrackIsAnInputError) {
    tinygltf::Model model = camera_model();
    tinygltf::Light lamp;
    lamp.type = "point";
    lamp.intensity = 683;
    add_light_shining_down(model, lamp, "Lamp", {0, 3, 0});
    add_animation(model, int(model.nodes.size()) - 1, "translation", "LINEAR", {0, 1}, {0, 3, 0, std::nanf(""), 3, 0});
    const std::string path = write(model, "lamp.glb");
    const std::string message = testing::input_error_of([&] { load_scene_desc(path); });
    EXPECT_NE(message.find("lamp.glb: light \"light 0\": transform is not finite at frame"), std::string::npos)
        << message;
}

TEST_F(GltfLoader, CubicSplineTranslationFollowsTheGltfHermiteSpline) {
    tinygltf::Model model;
    const int node = add_node(model, make_node("Spline", add_triangle_mesh(model)));
    // Per key: in-tangent, value, out-tangent. The outer tangents (9) must not matter.
    add_animation(model, node, "translation", "CUBICSPLINE", {0, 2},
                  {9, 9, 9, 0, 0, 0, 1, 0, 0, /**/ 0, 0, 0, 1, 0, 0, 9, 9, 9});
    for (const Loaded& loaded : write_and_load(model)) {
        SCOPED_TRACE(loaded.path);
        const ObjectDesc& spline = find_object(loaded.desc, "Spline");
        // glTF 2.0 Appendix C at s = 1/2 with dt = 2: p = (2s³-3s²+1) p0 + (s³-2s²+s) dt b0
        // + (-2s³+3s²) p1 + (s³-s²) dt a1 = 0 + 0.125 * 2 + 0.5 * 1 + 0 = 0.75.
        expect_near(world_vertex(spline, 0, 1), {0.75f, 0, 0});
        expect_near(world_vertex(spline, 0, 2), {1, 0, 0});
    }
}

TEST_F(GltfLoader, CubicSplineRotationIsInterpolatedComponentwiseThenNormalised) {
    tinygltf::Model model;
    const int node = add_node(model, make_node("Spin", add_triangle_mesh(model)));
    const float s = std::sin(pi / 4), c = std::cos(pi / 4);
    // Zero tangents inside the segment; the outer ones (5) must neither matter nor be normalised.
    add_animation(model, node, "rotation", "CUBICSPLINE", {0, 1},
                  {5, 5, 5, 5, 0, 0, 0, 1, 0, 0, 0, 0, /**/ 0, 0, 0, 0, 0, 0, s, c, 5, 5, 5, 5});
    for (const Loaded& loaded : write_and_load(model)) {
        SCOPED_TRACE(loaded.path);
        const ObjectDesc& spin = find_object(loaded.desc, "Spin");
        // Half-way, (q0 + q1) / 2 normalised is the 45° rotation.
        expect_near(world_vertex(spin, 1, 0.5f), {std::cos(pi / 4), std::sin(pi / 4), 0});
        EXPECT_FLOAT_EQ(spin.placement[0].rotation_track->values[0].x, 5);
    }
}

TEST_F(GltfLoader, NormalisedShortRotationsAreDecoded) {
    tinygltf::Model model;
    const int node = add_node(model, make_node("Turner", add_triangle_mesh(model)));
    add_animation(model, node, "rotation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0, 0, 1});
    // Replace the float output by shorts: identity, then 90° about +z.
    const int16_t shorts[] = {0, 0, 0, 32767, 0, 0, 23170, 23170};
    const int output = add_accessor(model, shorts, sizeof shorts, TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC4, 2);
    model.accessors[size_t(output)].normalized = true;
    model.animations[0].samplers[0].output = output;
    for (const Loaded& loaded : write_and_load(model))
        expect_near(world_vertex(find_object(loaded.desc, "Turner"), 1, 1), {0, 1, 0}, 1e-4f);
}

TEST_F(GltfLoader, DurationIsTheEndOfTheLongestAnimation) {
    tinygltf::Model model;
    const int mesh = add_triangle_mesh(model);
    const int a = add_node(model, make_node("A", mesh));
    const int b = add_node(model, make_node("B", mesh));
    add_animation(model, a, "translation", "LINEAR", {0, 2}, {0, 0, 0, 1, 0, 0});
    add_animation(model, b, "scale", "LINEAR", {0.5f, 3.5f}, {1, 1, 1, 2, 2, 2});
    for (const Loaded& loaded : write_and_load(model)) EXPECT_FLOAT_EQ(loaded.duration_s, 3.5f);
}

TEST_F(GltfLoader, LaterChannelWinsWhenTwoTargetTheSamePath) {
    tinygltf::Model model;
    const int node = add_node(model, make_node("Tri", add_triangle_mesh(model)));
    add_animation(model, node, "translation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0});
    add_animation(model, node, "translation", "LINEAR", {0, 1}, {0, 0, 0, -1, 0, 0});
    for (const Loaded& loaded : write_and_load(model))
        expect_near(world_vertex(find_object(loaded.desc, "Tri"), 0, 1), {-1, 0, 0});
}

TEST_F(GltfLoader, JsonSceneIncludesGltfRelativeToItselfAndOverridesTheResolution) {
    tinygltf::Model model = camera_model();
    const int node = add_node(model, make_node("Tri", add_triangle_mesh(model)));
    add_animation(model, node, "translation", "LINEAR", {0, 2}, {0, 0, 0, 1, 0, 0});
    fs::create_directories(m_dir / "assets");
    write(model, "assets/model.glb");
    const fs::path json = m_dir / "scene.json";
    std::ofstream(json) << R"({"gltf": "assets/model.glb", "camera": {"resolution": [640, 480]}})";
    const SceneDesc desc = load_scene_desc(json.string());
    EXPECT_EQ(desc.objects.size(), 1u);
    EXPECT_EQ(desc.frame_count, 49);  // 2 s at the default 24 fps, both ends included
    EXPECT_EQ(desc.camera.height, 480);
    EXPECT_NEAR(desc.camera.fov_y_deg, 60, 1e-4);
    expect_near(evaluate_chain(desc.camera.placement, 0).point({}), {0, 1, 5});
}

/// `count` key times `1 / fps` apart from `start_s`, and translations along x for them.
std::pair<std::vector<float>, std::vector<float>> sampled_keys(float fps, int count, float start_s) {
    std::vector<float> times, values;
    for (int k = 0; k < count; ++k) {
        times.push_back(start_s + float(k) / fps);
        values.insert(values.end(), {float(k), 0, 0});
    }
    return {times, values};
}

TEST_F(GltfLoader, GlbRendersAsAWholeSceneAtTheRateItsKeysWereSampledAt) {
    tinygltf::Model model = camera_model();
    const int node = add_node(model, make_node("Cube", add_triangle_mesh(model)));
    const auto [times, values] = sampled_keys(30, 24, 1 / 30.0f);  // Blender: frames 1-24 at 30 fps
    add_animation(model, node, "translation", "LINEAR", times, values);
    write(model, "blender.glb");
    const SceneDesc desc = load_scene_desc((m_dir / "blender.glb").string());
    EXPECT_EQ(desc.name, "blender");
    EXPECT_FLOAT_EQ(desc.fps, 30);
    EXPECT_EQ(desc.frame_count, 25);  // 0.8 s at 30 fps, both ends included
    EXPECT_EQ(desc.fps_source, FpsSource::gltf_keys);
    EXPECT_TRUE(find_object(desc, "Cube").is_dynamic());
}

TEST_F(GltfLoader, UnevenOrRareKeysKeepTheDefaultRate) {
    tinygltf::Model model = camera_model();
    const int a = add_node(model, make_node("A", add_triangle_mesh(model)));
    add_animation(model, a, "translation", "LINEAR", {0, 1, 2}, {0, 0, 0, 1, 0, 0, 2, 0, 0});  // 1 fps
    write(model, "rare.glb");
    EXPECT_FLOAT_EQ(load_scene_desc((m_dir / "rare.glb").string()).fps, 24);
    const auto [times, values] = sampled_keys(25, 10, 0);
    const int b = add_node(model, make_node("B", add_triangle_mesh(model)));
    add_animation(model, b, "translation", "LINEAR", times, values);  // 25 fps disagrees with 1 fps
    write(model, "mixed.glb");
    EXPECT_FLOAT_EQ(load_scene_desc((m_dir / "mixed.glb").string()).fps, 24);
}

/// `count` key times `1 / fps` apart from 0, summed in float32 one step at a time, as an
/// exporter that accumulates its time step writes them.
std::vector<float> summed_key_times(float fps, int count) {
    std::vector<float> times = {0};
    const float step_s = 1 / fps;
    while (times.size() < size_t(count)) times.push_back(times.back() + step_s);
    return times;
}

/// camera_model() plus one triangle per entry of `key_times`, moved by a LINEAR sampler with
/// those key times.
tinygltf::Model keyed_model(const std::vector<std::vector<float>>& key_times) {
    tinygltf::Model model = camera_model();
    const int mesh = add_triangle_mesh(model);
    for (const std::vector<float>& times : key_times) {
        const int node = add_node(model, make_node("Mover", mesh));
        add_animation(model, node, "translation", "LINEAR", times, std::vector<float>(3 * times.size(), 0));
    }
    return model;
}

/// Frame rates from key spacings: each test loads keyed_model() as a whole scene.
class GltfFrameRate : public GltfLoader {
protected:
    SceneDesc load_keyed(const std::vector<std::vector<float>>& key_times) const {
        return load_scene_desc(write(keyed_model(key_times), "keys.glb"));
    }
};

TEST_F(GltfFrameRate, KeysEvery39thOfASecondGive39FpsAnd40Frames) {
    // Both ways an exporter may write float32 times: k / 39 rounded once, or 1/39 summed k times.
    for (const std::vector<float>& times : {sampled_keys(39, 40, 0).first, summed_key_times(39, 40)}) {
        const SceneDesc desc = load_keyed({times});
        EXPECT_EQ(desc.fps, 39);
        EXPECT_EQ(desc.fps_source, FpsSource::gltf_keys);
        EXPECT_EQ(describe_fps_source(desc), "from the glTF keys, one every 1/39 s");
        EXPECT_EQ(desc.frame_count, 40);
        EXPECT_NEAR(desc.frame_time_s(39), times.back(), 1e-6);  // the last frame shows the last key
    }
}

TEST_F(GltfFrameRate, KeysEvery59thOfASecondGive59FpsAnd60Frames) {
    // Keys from 0, and Blender's frames 1-59 (frame f at f / 59 s): both end at 1 s.
    for (const auto& [count, start_s] : {std::pair{60, 0.0f}, std::pair{59, 1 / 59.0f}}) {
        const SceneDesc desc = load_keyed({sampled_keys(59, count, start_s).first});
        EXPECT_EQ(desc.fps, 59);
        EXPECT_EQ(desc.frame_count, 60);
    }
}

TEST_F(GltfFrameRate, KeysAt24And30FpsStillGiveThoseRates) {
    for (const int fps : {24, 30}) {
        const SceneDesc desc = load_keyed({sampled_keys(float(fps), 2 * fps + 1, 0).first});  // 2 s
        EXPECT_EQ(desc.fps, float(fps));
        EXPECT_EQ(desc.frame_count, 2 * fps + 1);
    }
}

TEST_F(GltfFrameRate, NtscKeysGiveTheirRateNotTheWholeOneNextToIt) {
    const float ntsc_fps = 30000 / 1001.0f;  // 29.97
    const SceneDesc desc = load_keyed({sampled_keys(ntsc_fps, 61, 0).first});
    EXPECT_NEAR(desc.fps, ntsc_fps, 1e-4f);
    EXPECT_EQ(desc.frame_count, 61);
    EXPECT_EQ(describe_fps_source(desc), "from the glTF keys, one every 1/29.97 s");
}

TEST_F(GltfFrameRate, FloatKeysSummedForFiveMinutesAt240FpsStayEven) {
    // Late intervals are off by up to 0.3% of the spacing: float32 rounding at 300 s.
    EXPECT_EQ(load_keyed({summed_key_times(240, 5 * 60 * 240 + 1)}).fps, 240);
}

TEST_F(GltfFrameRate, UnevenKeysKeepTheDefaultRate) {
    std::vector<float> jittered = sampled_keys(30, 31, 0).first;
    jittered[15] += 0.005f / 30;  // half a percent of the spacing
    for (const std::vector<float>& times : {std::vector<float>{0, 0.04f, 0.09f, 0.125f}, jittered}) {
        const SceneDesc desc = load_keyed({times});
        EXPECT_EQ(desc.fps, 24);
        EXPECT_EQ(desc.fps_source, FpsSource::default_rate);
    }
}

TEST_F(GltfFrameRate, SamplersWithDifferentSpacingsKeepTheDefaultRate) {
    for (const float other_fps : {25.0f, 30.5f}) {
        const SceneDesc desc = load_keyed({sampled_keys(30, 31, 0).first, sampled_keys(other_fps, 20, 0).first});
        EXPECT_EQ(desc.fps, 24);
        EXPECT_EQ(desc.fps_source, FpsSource::default_rate);
        EXPECT_EQ(desc.frame_count, 25);  // 1 s at 24 fps
    }
}

TEST_F(GltfFrameRate, SamplersWithTwoKeysDoNotDecideTheRate) {
    // Two keys are any two moments; only the sampled channel speaks of a rate.
    const SceneDesc desc = load_keyed({{0, 0.77f}, sampled_keys(39, 40, 0).first, {0.1f, 0.35f}});
    EXPECT_EQ(desc.fps, 39);
    EXPECT_EQ(desc.frame_count, 40);
}

TEST_F(GltfFrameRate, RatesOutside10To240FpsKeepTheDefault) {
    for (const float fps : {1.0f, 5.0f, 9.9f, 250.0f, 480.0f}) {
        const SceneDesc desc = load_keyed({sampled_keys(fps, 5, 0).first});
        EXPECT_EQ(desc.fps, 24) << fps << " fps";
        EXPECT_EQ(desc.fps_source, FpsSource::default_rate) << fps << " fps";
    }
    for (const float fps : {10.0f, 240.0f}) EXPECT_EQ(load_keyed({sampled_keys(fps, 5, 0).first}).fps, fps);
}

TEST_F(GltfFrameRate, SceneFileFpsOverridesTheKeyRateAndACountAloneKeepsIt) {
    write(keyed_model({sampled_keys(39, 40, 0).first}), "keys.glb");
    const fs::path json = m_dir / "scene.json";
    std::ofstream(json) << R"({"gltf": "keys.glb", "frames": {"fps": 24}})";
    const SceneDesc overridden = load_scene_desc(json.string());
    EXPECT_EQ(overridden.fps, 24);
    EXPECT_EQ(overridden.fps_source, FpsSource::scene_file);
    EXPECT_EQ(overridden.frame_count, 25);  // 1 s at 24 fps
    std::ofstream(json) << R"({"gltf": "keys.glb", "frames": {"count": 10}})";
    const SceneDesc counted = load_scene_desc(json.string());
    EXPECT_EQ(counted.fps, 39);
    EXPECT_EQ(counted.fps_source, FpsSource::gltf_keys);
    EXPECT_EQ(counted.frame_count, 10);
}

TEST_F(GltfLoader, GlbWithoutCameraCannotBeAScene) {
    tinygltf::Model model;
    add_node(model, make_node("Tri", add_triangle_mesh(model)));
    const std::string path = write(model, "nocamera.glb");
    try {
        load_scene_desc(path);
        ADD_FAILURE() << "loaded without an error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("nocamera.glb: the file has no perspective camera"), std::string::npos)
            << e.what();
    }
}

// ---------------------------------------------------------------------------------------------
// Malformed files

TEST_F(GltfLoader, MissingFileThrowsInputErrorNamingIt) {
    expect_input_error((m_dir / "absent.glb").string(), "not found");
}

// External buffers and images are read as every input file is: only regular files (a buffer
// named by a path up to /dev/zero, or a FIFO beside the file, is refused, not read).
TEST_F(GltfLoader, ExternalBufferThatIsADeviceOrAFifoIsRefusedNotRead) {
    const auto with_buffer = [&](const std::string& uri) {
        const std::string path = (m_dir / "external.gltf").string();
        std::ofstream(path) << R"({"asset": {"version": "2.0"}, "buffers": [{"uri": ")" + uri +
                                   R"(", "byteLength": 4}]})";
        return path;
    };
    expect_input_error(with_buffer(fs::relative("/dev/zero", m_dir).string()), "not a regular file: it is a device");
    ASSERT_EQ(::mkfifo((m_dir / "pipe.bin").c_str(), 0600), 0);
    expect_input_error(with_buffer("pipe.bin"), "pipe.bin: not a regular file: it is a FIFO");
}

// With --confine-inputs a buffer outside the glTF file's folder is refused.
TEST_F(GltfLoader, ConfinedInputsRefuseABufferOutsideTheFolder) {
    fs::create_directories(m_dir / "scene");
    std::ofstream(m_dir / "outside.bin") << "abcd";
    const std::string path = (m_dir / "scene" / "model.gltf").string();
    std::ofstream(path) << R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "../outside.bin", "byteLength": 4}]})";
    SceneDesc desc;
    bool has_camera = false;
    EXPECT_NO_THROW(append_gltf(path, desc, has_camera));
    const std::string message =
        testing::input_error_of([&] { append_gltf(path, desc, has_camera, InputFolder::of_scene(path)); });
    EXPECT_NE(message.find("lies outside the scene file's folder"), std::string::npos) << message;
}

TEST_F(GltfLoader, UnknownExtensionThrowsInputError) {
    expect_input_error(write(camera_model(), "scene.obj"), "extension");
}

TEST_F(GltfLoader, TruncatedGlbThrowsInputError) {
    tinygltf::Model model;
    add_node(model, make_node("Tri", add_triangle_mesh(model)));
    std::ifstream in(write(model, "whole.glb"), std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
    const std::string path = (m_dir / "half.glb").string();
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() / 2));
    expect_input_error(path, "");
}

TEST_F(GltfLoader, AccessorPastTheEndOfItsBufferThrowsInputError) {
    tinygltf::Model model;
    add_node(model, make_node("Tri", add_triangle_mesh(model)));
    model.accessors[0].count = 100;  // positions
    for (const std::string& path : write_both(model)) expect_input_error(path, "past the end");
}

TEST_F(GltfLoader, NonIncreasingKeyTimesThrowInputError) {
    tinygltf::Model model;
    const int node = add_node(model, make_node("Tri", add_triangle_mesh(model)));
    add_animation(model, node, "translation", "LINEAR", {0, 1, 1}, {0, 0, 0, 1, 0, 0, 2, 0, 0});
    for (const std::string& path : write_both(model)) expect_input_error(path, "strictly increasing");
}

}  // namespace
}  // namespace steadylight
