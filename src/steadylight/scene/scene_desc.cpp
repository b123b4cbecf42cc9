#include "steadylight/scene/scene_desc.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "steadylight/base/error.h"
#include "steadylight/scene/gltf_loader.h"
#include "steadylight/scene/json_reader.h"
#include "steadylight/scene/shapes.h"
#include "steadylight/scene/sky_nishita.h"
#include "steadylight/scene/world_image.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

std::string resolve_path(const JsonObject& json, const std::string& key) {
    const fs::path file = json.string(key);
    const fs::path base = fs::path(json.file()).parent_path();
    return file.is_absolute() ? file.string() : (base / file).lexically_normal().string();
}

Quat quat_from_numbers(const std::vector<float>& v, const JsonObject& json, const std::string& key) {
    if (v.size() != 4) json.fail(key, "a quaternion needs 4 numbers [x, y, z, w]");
    const Quat q{v[0], v[1], v[2], v[3]};
    if (dot(q, q) < 1e-12f) json.fail(key, "quaternion must not be zero");
    return normalize(q);
}

/// A rotation is a quaternion [x, y, z, w] or {"axis": [x, y, z], "degrees": a}.
Quat parse_rotation(const JsonObject& json, const std::string& key) {
    if (!json.has(key)) return {};
    if (json.is_array(key)) return quat_from_numbers(json.numbers(key), json, key);
    const JsonObject rotation = json.object(key);
    const Vec3 axis = rotation.vec3("axis");
    if (length(axis) == 0) rotation.fail("axis", "rotation axis must not be zero");
    const Quat q = Quat::from_axis_angle(axis, rotation.number("degrees") * pi / 180);
    rotation.warn_unread();
    return q;
}

Interpolation parse_interpolation(const JsonObject& json) {
    const std::string name = json.string("interpolation", "linear");
    if (name == "linear") return Interpolation::linear;
    if (name == "step") return Interpolation::step;
    json.fail("interpolation", "unknown interpolation \"" + name + "\" (linear or step)");
}

/// A track whose `values` are already read: its interpolation and times, checked against them.
template <class T>
Track<T> parse_track_keys(const JsonObject& json, std::vector<T> values) {
    Track<T> track;
    track.interpolation = parse_interpolation(json);
    track.times = json.numbers("times");
    track.values = std::move(values);
    if (track.times.empty()) json.fail("times", "a track needs at least one key");
    if (track.times.size() != track.values.size())
        json.fail("values", "has " + std::to_string(track.values.size()) + " entries for " +
                                std::to_string(track.times.size()) + " times");
    for (size_t i = 1; i < track.times.size(); ++i)
        if (!(track.times[i] > track.times[i - 1])) json.fail("times", "times must be strictly increasing");
    json.warn_unread();
    return track;
}

template <class T>
Track<T> parse_track(const JsonObject& json, size_t size, T (*convert)(const std::vector<float>&)) {
    std::vector<T> values;
    for (const std::vector<float>& v : json.tuples("values", size)) values.push_back(convert(v));
    return parse_track_keys(json, std::move(values));
}

/// A track of emitted radiance or intensity: values [r, g, b] or one number, none negative.
Track<Rgb> parse_light_track(const JsonObject& json, const std::string& what) {
    std::vector<Rgb> values = json.rgbs("values");
    for (size_t i = 0; i < values.size(); ++i)
        for (int c = 0; c < 3; ++c)
            if (values[i][c] < 0) json.fail("values/" + std::to_string(i), what + " must not be negative");
    return parse_track_keys(json, std::move(values));
}

Vec3 vec3_from(const std::vector<float>& v) { return {v[0], v[1], v[2]}; }

/// A track of quaternions [x, y, z, w], none of them zero (it would turn nothing into nowhere).
Track<Quat> parse_rotation_track(const JsonObject& json) {
    std::vector<Quat> values;
    const std::vector<std::vector<float>> keys = json.tuples("values", 4);
    for (size_t i = 0; i < keys.size(); ++i)
        values.push_back(quat_from_numbers(keys[i], json, "values/" + std::to_string(i)));
    return parse_track_keys(json, std::move(values));
}

/// "transform": {translation, rotation, scale}.
AnimatedTrs parse_transform(const JsonObject& json) {
    AnimatedTrs trs;
    if (!json.has("transform")) return trs;
    const JsonObject transform = json.object("transform");
    trs.translation = transform.vec3("translation", {});
    trs.rotation = parse_rotation(transform, "rotation");
    trs.scale = transform.vec3("scale", {1, 1, 1});
    transform.warn_unread();
    return trs;
}

/// The translation, rotation and scale tracks of an "animation" object; a track replaces the
/// fixed value of its component.
void parse_trs_tracks(const JsonObject& animation, AnimatedTrs& trs) {
    if (animation.has("translation"))
        trs.translation_track = parse_track<Vec3>(animation.object("translation"), 3, vec3_from);
    if (animation.has("rotation")) trs.rotation_track = parse_rotation_track(animation.object("rotation"));
    if (animation.has("scale")) trs.scale_track = parse_track<Vec3>(animation.object("scale"), 3, vec3_from);
}

/// A light's "translation" (when it has a position) and "rotation" tracks; lights have no size,
/// so no "scale".
void parse_light_motion(const JsonObject& animation, AnimatedTrs& trs, bool has_position) {
    if (animation.has("scale")) animation.fail("scale", "a light has no size to scale");
    if (animation.has("translation") && !has_position)
        animation.fail("translation", "a sun has no position; a rotation track turns its direction");
    parse_trs_tracks(animation, trs);
}

/// "transform" and "animation" (translation, rotation and scale tracks only).
AnimatedTrs parse_placement(const JsonObject& json) {
    AnimatedTrs trs = parse_transform(json);
    if (json.has("animation")) {
        const JsonObject animation = json.object("animation");
        parse_trs_tracks(animation, trs);
        animation.warn_unread();
    }
    return trs;
}

MaterialDesc parse_material(const std::string& name, const JsonObject& json) {
    MaterialDesc m;
    m.name = name;
    const std::string type = json.string("type");
    if (type == "lambert") {
        m.type = MaterialType::lambert;
    } else if (type == "mirror") {
        m.type = MaterialType::mirror;
        m.reflectance = {1, 1, 1};
    } else if (type == "dielectric") {
        m.type = MaterialType::dielectric;
        m.roughness = 0;  // smooth unless the scene says otherwise
        m.attenuation_color = json.rgb("attenuation_color", m.attenuation_color);
        m.attenuation_distance = json.number("attenuation_distance", m.attenuation_distance);
        if (!(m.attenuation_distance > 0)) json.fail("attenuation_distance", "must be positive");
    } else if (type == "glossy") {
        m.type = MaterialType::glossy;
        m.reflectance = {0.9f, 0.9f, 0.9f};
    } else if (type == "pbr") {
        m.type = MaterialType::pbr;
        m.roughness = 0.5f;
        m.metallic = json.number("metallic", m.metallic);
        m.specular = json.number("specular", m.specular);
        if (!(m.metallic >= 0 && m.metallic <= 1)) json.fail("metallic", "must lie in [0, 1]");
        if (!(m.specular >= 0 && m.specular <= 1)) json.fail("specular", "must lie in [0, 1]");
    } else {
        json.fail("type", "unknown material type \"" + type + "\" (lambert, mirror, dielectric, glossy, pbr)");
    }
    m.reflectance = json.rgb("reflectance", m.reflectance);
    m.transmittance = json.rgb("transmittance", m.transmittance);
    m.ior = json.number("ior", m.ior);
    m.roughness = json.number("roughness", m.roughness);
    for (int c = 0; c < 3; ++c) {
        if (m.reflectance[c] < 0 || m.reflectance[c] > 1) json.fail("reflectance", "must lie in [0, 1]");
        if (m.transmittance[c] < 0 || m.transmittance[c] > 1) json.fail("transmittance", "must lie in [0, 1]");
        if (m.attenuation_color[c] < 0 || m.attenuation_color[c] > 1)
            json.fail("attenuation_color", "must lie in [0, 1]");
    }
    if (!(m.ior > 0)) json.fail("ior", "must be positive");
    const bool smooth_allowed = m.type == MaterialType::dielectric;
    if (!((m.roughness > 0 || (smooth_allowed && m.roughness == 0)) && m.roughness <= 1))
        json.fail("roughness", smooth_allowed ? "must lie in [0, 1]" : "must lie in (0, 1]");
    json.warn_unread();
    return m;
}

Geometry parse_shape(const JsonObject& json, const InputFolder& inputs) {
    const std::string type = json.string("type");
    Geometry geometry;
    if (type == "quad") {
        geometry = make_quad(json.vec3("corner"), json.vec3("edge_u"), json.vec3("edge_v"));
    } else if (type == "box") {
        const Vec3 size = json.vec3("size");
        if (!(size.x > 0 && size.y > 0 && size.z > 0)) json.fail("size", "box sizes must be positive");
        geometry = make_box(json.vec3("center", {}), size);
    } else if (type == "sphere") {
        const float radius = json.number("radius");
        if (!(radius > 0)) json.fail("radius", "must be positive");
        geometry = Sphere{json.vec3("center", {}), radius};
    } else if (type == "mesh") {
        const std::string file = resolve_path(json, "file");
        std::error_code error;  // a name too long for the file system is "not found" too
        if (!fs::exists(file, error)) json.fail("file", "mesh file \"" + file + "\" not found");
        try {
            geometry = load_obj_mesh(file, inputs);
        } catch (const InputError& e) {
            json.fail("file", e.what());  // the mesh's own message, and where the scene names it
        }
    } else {
        json.fail("type", "unknown shape type \"" + type + "\" (quad, box, sphere, mesh)");
    }
    json.warn_unread();
    return geometry;
}

ObjectDesc parse_object(const JsonObject& json, const std::map<std::string, int>& materials, int black_material,
                        const InputFolder& inputs, int index) {
    ObjectDesc object;
    object.name = json.string("name", "object" + std::to_string(index));
    object.geometry = parse_shape(json.object("shape"), inputs);
    object.emission = json.rgb("emission", {});
    for (int c = 0; c < 3; ++c)
        if (object.emission[c] < 0) json.fail("emission", "radiance must not be negative");
    object.two_sided_emission = json.boolean("two_sided", false);
    // The placement and its tracks, and an emission track, which says whether this is a light.
    object.placement = {parse_transform(json)};
    if (json.has("animation")) {
        const JsonObject animation = json.object("animation");
        parse_trs_tracks(animation, object.placement[0]);
        if (animation.has("emission"))
            object.emission_track = parse_light_track(animation.object("emission"), "radiance");
        animation.warn_unread();
    }
    if (json.has("material")) {
        const std::string material = json.string("material");
        const auto it = materials.find(material);
        if (it == materials.end()) json.fail("material", "unknown material \"" + material + "\"");
        object.material = it->second;
    } else if (object.is_emitter()) {
        object.material = black_material;  // an emitter without a material reflects nothing
    } else {
        json.fail("material", "missing required field");
    }
    object.marked_dynamic = json.boolean("dynamic", false);
    json.warn_unread();
    return object;
}

PointLightDesc parse_point_light(const JsonObject& json) {
    PointLightDesc light;
    const std::string type = json.string("type");
    if (type == "point") {
        light.type = PointLightType::point;
    } else if (type == "spot") {
        light.type = PointLightType::spot;
        light.direction = json.vec3("direction");
        if (length(light.direction) == 0) json.fail("direction", "must not be zero");
        light.direction = normalize(light.direction);
        light.cone_angle_deg = json.number("cone_degrees", light.cone_angle_deg);
        light.falloff_start_deg = json.number("falloff_start_degrees", light.cone_angle_deg * 0.8f);
        if (!(light.cone_angle_deg > 0 && light.cone_angle_deg <= 90)) json.fail("cone_degrees", "must lie in (0, 90]");
        if (!(light.falloff_start_deg >= 0 && light.falloff_start_deg <= light.cone_angle_deg))
            json.fail("falloff_start_degrees", "must lie in [0, cone_degrees]");
    } else {
        json.fail("type", "unknown light type \"" + type + "\" (point, spot or sun)");
    }
    light.name = json.string("name", type);
    // The position is the placement's translation, so that a translation track replaces it; a
    // rotation track turns the direction.
    AnimatedTrs placement{.translation = json.vec3("position")};
    light.intensity = json.rgb("intensity", {});
    for (int c = 0; c < 3; ++c)
        if (light.intensity[c] < 0) json.fail("intensity", "must not be negative");
    if (json.has("animation")) {
        const JsonObject animation = json.object("animation");
        parse_light_motion(animation, placement, true);
        if (animation.has("intensity"))
            light.intensity_track = parse_light_track(animation.object("intensity"), "intensity");
        animation.warn_unread();
    }
    light.placement = {placement};
    json.warn_unread();
    return light;
}

CameraDesc parse_camera(const JsonObject& json, const CameraDesc& fallback) {
    CameraDesc camera = fallback;
    camera.fov_y_deg = json.number("fov_y", camera.fov_y_deg);
    if (!(camera.fov_y_deg > 0 && camera.fov_y_deg < 180)) json.fail("fov_y", "must lie in (0, 180) degrees");
    if (json.has("resolution")) {
        const std::vector<float> r = json.numbers("resolution");
        if (r.size() != 2 || r[0] < 1 || r[1] < 1 || r[0] > 65536 || r[1] > 65536 || r[0] != std::floor(r[0]) ||
            r[1] != std::floor(r[1]))
            json.fail("resolution", "expected [width, height] in whole pixels");
        camera.width = int(r[0]);
        camera.height = int(r[1]);
    }
    AnimatedTrs placement = parse_placement(json);
    if (json.has("position")) {
        // A look-at camera: the fixed placement comes from position, look_at and up.
        const Vec3 position = json.vec3("position");
        const Vec3 back = position - json.vec3("look_at");
        const Vec3 up = json.vec3("up", {0, 1, 0});
        if (length(back) == 0) json.fail("look_at", "must differ from position");
        const Vec3 right = cross(up, back);
        if (length(right) < 1e-6f * length(back) * length(up))
            json.fail("up", "must not be parallel to the view direction");
        placement.translation = position;
        placement.rotation = Quat::from_basis(normalize(right), normalize(cross(back, right)), normalize(back));
    }
    if (json.has("position") || json.has("transform") || json.has("animation") || camera.placement.empty())
        camera.placement = {placement};
    json.warn_unread();
    return camera;
}

void validate_mesh(const TriangleMesh& mesh, const std::string& where) {
    if (mesh.indices.size() % 3 != 0) throw InputError(where, "triangle indices are not a multiple of 3");
    for (const int i : mesh.indices)
        if (i < 0 || size_t(i) >= mesh.positions.size()) throw InputError(where, "triangle index out of range");
    for (const Vec3& p : mesh.positions)
        if (!is_finite(p)) throw InputError(where, "vertex position is not finite");
    if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size())
        throw InputError(where, "normal count differs from vertex count");
    const size_t n = mesh.positions.size();
    if ((!mesh.uv0.empty() && mesh.uv0.size() != n) || (!mesh.uv1.empty() && mesh.uv1.size() != n) ||
        (!mesh.colors.empty() && mesh.colors.size() != n) || (!mesh.tangents.empty() && mesh.tangents.size() != n))
        throw InputError(where, "texture coordinate, colour or tangent count differs from vertex count");
    for (const Vec3& normal : mesh.normals)
        if (!is_finite(normal)) throw InputError(where, "vertex normal is not finite");
}

void validate_placement(const std::vector<AnimatedTrs>& chain, const SceneDesc& desc, const std::string& where) {
    for (int frame = 0; frame < desc.frame_count; ++frame) {
        const Transform t = evaluate_chain(chain, desc.frame_time_s(frame));
        if (!t.is_finite()) throw InputError(where, "transform is not finite at frame " + std::to_string(frame));
        if (std::abs(t.determinant()) < 1e-12f)
            throw InputError(where, "transform is singular (zero scale) at frame " + std::to_string(frame));
    }
}

/// The checks the parser makes on a light track, for tracks built in code or by other loaders.
void validate_light_track(const std::optional<Track<Rgb>>& track, const std::string& where) {
    if (!track) return;
    const size_t per_key = track->interpolation == Interpolation::cubic_spline ? 3 : 1;
    if (track->times.empty() || track->values.size() != per_key * track->times.size())
        throw InputError(where, "light track needs keys and one value per key");
    for (size_t i = 0; i < track->times.size(); ++i)
        if (!std::isfinite(track->times[i]) || (i > 0 && !(track->times[i] > track->times[i - 1])))
            throw InputError(where, "light track times must be finite and strictly increasing");
    for (const Rgb& value : track->values)
        if (!is_finite(value) || value.r < 0 || value.g < 0 || value.b < 0)
            throw InputError(where, "light track values must be finite and not negative");
}

}  // namespace

Rgb MaterialDesc::absorption() const {
    if (type != MaterialType::dielectric || !(attenuation_distance > 0) || std::isinf(attenuation_distance)) return {};
    // A black channel absorbs all of its light within a few attenuation distances.
    const auto sigma = [&](float colour) { return -std::log(std::max(colour, 1e-6f)) / attenuation_distance; };
    return {sigma(attenuation_color.r), sigma(attenuation_color.g), sigma(attenuation_color.b)};
}

PointLightPose PointLightDesc::pose_at(float time_s) const {
    const Transform world_from_light = evaluate_chain(placement, time_s);
    return {.position = world_from_light.point(position),
            .direction = normalize(world_from_light.vector(direction)),
            .intensity = intensity_at(time_s)};
}

Vec3 SunLightDesc::direction_at(float time_s) const {
    return normalize(evaluate_chain(placement, time_s).vector(direction));
}

bool is_ever_lit(const Track<Rgb>& track) {
    return std::any_of(track.values.begin(), track.values.end(), [](Rgb value) { return !is_black(value); });
}

namespace {

/// `text` as a message may show it: control characters as \xNN, and at most 60 bytes.
std::string printable(const std::string& text) {
    std::string out;
    for (const char c : text.substr(0, 60))
        out += (unsigned char)c < 0x20 || c == 0x7f ? fmt::format("\\x{:02x}", (unsigned char)c) : std::string(1, c);
    return text.size() > 60 ? out + "..." : out;
}

}  // namespace

void check_scene_name(const std::string& name, const std::string& where) {
    const auto refuse = [&](const std::string& why) {
        throw InputError(where,
                         fmt::format("the scene name \"{}\" {}: it names the output files", printable(name), why));
    };
    if (name.empty()) refuse("is empty");
    if (name == "." || name == "..") refuse("is a folder's name");
    if (name.find_first_of("/\\") != std::string::npos) refuse("holds a path separator");
    if (std::any_of(name.begin(), name.end(), [](char c) { return (unsigned char)c < 0x20 || c == 0x7f; }))
        refuse("holds a control character");
    if (name.size() > max_scene_name_bytes)
        refuse(fmt::format("is {} bytes long, more than {}", name.size(), max_scene_name_bytes));
}

void validate(const SceneDesc& desc) {
    const std::string& file = desc.source_file;
    if (desc.frame_count < 1) throw InputError(file, "the scene has no frames");
    if (desc.frame_count > max_frame_count)
        throw InputError(file, fmt::format("{} frames: an animation has at most {} (11.5 hours at 24 fps); split it "
                                           "into several scenes",
                                           desc.frame_count, max_frame_count));
    if (desc.camera.placement.empty()) throw InputError(file, "the scene has no camera");
    validate_placement(desc.camera.placement, desc, file + ": camera");
    for (const TextureImage& image : desc.images)
        if (image.width < 1 || image.height < 1 || image.rgba.size() != size_t(image.width) * size_t(image.height) * 4)
            throw InputError(file + ": image \"" + image.name + "\"", "pixel data does not match its size");
    for (const MaterialDesc& m : desc.materials)
        for (const TextureRef* t :
             {&m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture, &m.emissive_texture})
            if (t->image >= int(desc.images.size()) || t->texcoord < 0 || t->texcoord > 1)
                throw InputError(file + ": material \"" + m.name + "\"",
                                 "texture image or texture coordinate set out of range");
    for (const ObjectDesc& object : desc.objects) {
        const std::string where = file + ": object \"" + object.name + "\"";
        if (object.material < 0 || size_t(object.material) >= desc.materials.size())
            throw InputError(where, "material index out of range");
        if (!is_finite(object.emission)) throw InputError(where, "emission is not finite");
        validate_light_track(object.emission_track, where + " emission");
        validate_placement(object.placement, desc, where);
        float area = 0;
        if (const auto* mesh = std::get_if<TriangleMesh>(&object.geometry)) {
            validate_mesh(*mesh, where);
            area = mesh_area(*mesh);
        } else {
            const Sphere& sphere = std::get<Sphere>(object.geometry);
            if (!is_finite(sphere.center) || !(sphere.radius > 0 && std::isfinite(sphere.radius)))
                throw InputError(where, "sphere needs a finite centre and a positive radius");
            area = 4 * pi * sphere.radius * sphere.radius;
        }
        if (object.is_emitter() && !(area > 0)) throw InputError(where, "emitter has zero area");
    }
    for (const PointLightDesc& light : desc.point_lights) {
        const std::string where = file + ": light \"" + light.name + "\"";
        if (!is_finite(light.position) || !is_finite(light.intensity))
            throw InputError(where, "position or intensity is not finite");
        if (!is_finite(light.direction) || !(length(light.direction) > 0))
            throw InputError(where, "direction is not finite, or zero");
        validate_light_track(light.intensity_track, where + " intensity");
        validate_placement(light.placement, desc, where);
    }
    for (const SunLightDesc& sun : desc.suns) {
        const std::string where = file + ": sun \"" + sun.name + "\"";
        if (!is_finite(sun.direction) || !(length(sun.direction) > 0) || !is_finite(sun.irradiance))
            throw InputError(where, "direction or irradiance is not finite, or the direction is zero");
        validate_placement(sun.placement, desc, where);
    }
}

std::string describe_fps_source(const SceneDesc& desc) {
    switch (desc.fps_source) {
        case FpsSource::scene_file:
            return "from the scene file";
        case FpsSource::gltf_keys:
            return fmt::format("from the glTF keys, one every 1/{:.6g} s", desc.fps);
        case FpsSource::default_rate:
            break;
    }
    return "default";
}

WorldDesc WorldDesc::uniform(Rgb radiance) {
    return {
        .radiance = std::make_shared<EnvironmentMap>(radiance),
        .description = fmt::format("uniform radiance ({:.3g}, {:.3g}, {:.3g})", radiance.r, radiance.g, radiance.b)};
}

namespace {

SunLightDesc parse_sun_light(const JsonObject& json) {
    SunLightDesc sun;
    sun.name = json.string("name", "sun");
    sun.direction = json.vec3("direction");
    if (!(length(sun.direction) > 0)) json.fail("direction", "must not be zero: it is the way the light travels");
    sun.direction = normalize(sun.direction);
    sun.irradiance = json.rgb("irradiance", {});
    for (int c = 0; c < 3; ++c)
        if (sun.irradiance[c] < 0) json.fail("irradiance", "must not be negative");
    sun.angle_deg = json.number("angle_degrees", sun.angle_deg);
    if (json.has("animation")) {
        const JsonObject animation = json.object("animation");
        AnimatedTrs placement;
        parse_light_motion(animation, placement, false);
        animation.warn_unread();
        sun.placement = {placement};
    }
    if (!(sun.angle_deg >= 0 && sun.angle_deg <= SunLightDesc::max_angle_deg))
        json.fail("angle_degrees", fmt::format("must lie in [0, {}]", SunLightDesc::max_angle_deg));
    json.warn_unread();
    return sun;
}

/// An angle in degrees from `json`, finite and within [lo, hi].
float degrees_in(const JsonObject& json, const std::string& key, float fallback, float lo, float hi) {
    const float value = json.number(key, fallback);
    if (!(value >= lo && value <= hi)) json.fail(key, fmt::format("must lie in [{}, {}] degrees", lo, hi));
    return value;
}

/// A non-negative finite number from `json`.
float non_negative(const JsonObject& json, const std::string& key, float fallback) {
    const float value = json.number(key, fallback);
    if (!(value >= 0 && std::isfinite(value))) json.fail(key, "must be a finite number, not negative");
    return value;
}

/// Blender's Sky Texture, Nishita model ("sky": {"model": "nishita", ...}): Blender's parameter
/// names, angles in degrees as Blender's interface shows them. Its sun disc joins `suns`.
std::shared_ptr<const EnvironmentMap> parse_sky(const JsonObject& json, float strength, std::vector<SunLightDesc>& suns,
                                                std::string& description) {
    const std::string model = json.string("model", "nishita");
    if (model != "nishita")
        json.fail("model", fmt::format("unknown sky model \"{}\": steadylight knows \"nishita\" (Blender's default "
                                       "Sky Texture)",
                                       model));
    constexpr float to_radians = pi / 180;
    NishitaSkyParams sky;
    sky.sun_elevation = degrees_in(json, "sun_elevation", sky.sun_elevation / to_radians, -90, 90) * to_radians;
    sky.sun_rotation = degrees_in(json, "sun_rotation", sky.sun_rotation / to_radians, -360, 360) * to_radians;
    sky.sun_size = degrees_in(json, "sun_size", sky.sun_size / to_radians, 0, SunLightDesc::max_angle_deg) * to_radians;
    sky.sun_intensity = non_negative(json, "sun_intensity", sky.sun_intensity);
    sky.sun_disc = json.boolean("sun_disc", sky.sun_disc);
    sky.altitude = non_negative(json, "altitude", sky.altitude);
    sky.air_density = non_negative(json, "air_density", sky.air_density);
    sky.dust_density = non_negative(json, "dust_density", sky.dust_density);
    sky.ozone_density = non_negative(json, "ozone_density", sky.ozone_density);
    json.warn_unread();

    if (const std::optional<NishitaSun> sun = nishita_sky_sun(sky)) {
        // Cycles' disc is darkened towards its limb: its mean radiance is 0.8 times the centre's.
        const float solid_angle = 2 * pi * (1 - std::cos(sun->angle_radians / 2));
        suns.push_back({.name = "sky sun",
                        .direction = -sun->direction,
                        .irradiance = sun->radiance * (0.8f * solid_angle * strength),
                        .angle_deg = sun->angle_radians / to_radians});
    }
    description = fmt::format(
        "Nishita sky, sun elevation {:.3g} rotation {:.3g} size {:.3g} degrees, disc {}, "
        "strength {:.3g}",
        sky.sun_elevation / to_radians, sky.sun_rotation / to_radians, sky.sun_size / to_radians,
        sky.sun_disc ? "on (the sun \"sky sun\")" : "off", strength);
    return std::make_shared<EnvironmentMap>(nishita_sky_image(sky, WorldDesc::sky_image_width), strength, 0.0f);
}

/// "world": a uniform colour, an equirectangular image or a sky, times a strength.
WorldDesc parse_world(const JsonObject& json, std::vector<SunLightDesc>& suns, const InputFolder& inputs) {
    WorldDesc world;
    if (int(json.has("color")) + int(json.has("image")) + int(json.has("sky")) > 1)
        json.fail("", "give one of \"color\", \"image\" and \"sky\"");
    const float strength = json.number("strength", 1);
    if (!(strength >= 0 && strength <= WorldDesc::max_strength))
        json.fail("strength", fmt::format("must lie in [0, {:g}]", WorldDesc::max_strength));
    if (json.has("image")) {
        const std::string path = resolve_path(json, "image");
        Image image = load_world_image(path, inputs);
        const float rotation = degrees_in(json, "rotation_degrees", 0, -360, 360);
        world.description = fmt::format("image {} ({} x {}), strength {:.3g}, rotation {:.3g} degrees", path,
                                        image.width, image.height, strength, rotation);
        world.radiance = std::make_shared<EnvironmentMap>(std::move(image), strength, rotation);
    } else if (json.has("sky")) {
        world.radiance = parse_sky(json.object("sky"), strength, suns, world.description);
    } else {
        const Rgb color = json.rgb("color", {0.05f, 0.05f, 0.05f});  // Blender's default World
        for (int c = 0; c < 3; ++c)
            if (!(color[c] >= 0)) json.fail("color", "must not be negative");
        json.warn_unread();
        return WorldDesc::uniform(color * strength);
    }
    json.warn_unread();
    return world;
}

PortalDesc parse_portal(const JsonObject& json) {
    const PortalDesc portal{
        .corner = json.vec3("corner"), .edge_u = json.vec3("edge_u"), .edge_v = json.vec3("edge_v")};
    if (!(portal.area() > 0) || !std::isfinite(portal.area()))
        json.fail("", "a portal needs edges that span an area (edge_u x edge_v is zero)");
    if (std::abs(dot(portal.edge_u, portal.edge_v)) > 1e-3f * length(portal.edge_u) * length(portal.edge_v))
        json.fail("", "a portal is a rectangle: edge_u and edge_v must be at right angles");
    json.warn_unread();
    return portal;
}

/// A glTF's suns take the angles a wrapper JSON gives them by light node name
/// ("sun_angles_degrees": {"Sun": 1.5}): glTF carries no angle.
void apply_sun_angles(const JsonObject& root, SceneDesc& desc) {
    const JsonObject angles = root.object("sun_angles_degrees");
    for (const std::string& name : angles.keys()) {
        const auto sun =
            std::find_if(desc.suns.begin(), desc.suns.end(), [&name](const SunLightDesc& s) { return s.name == name; });
        if (sun == desc.suns.end()) angles.fail(name, "no sun light of that name in the scene");
        sun->angle_deg = angles.number(name);
        if (!(sun->angle_deg >= 0 && sun->angle_deg <= SunLightDesc::max_angle_deg))
            angles.fail(name, fmt::format("must lie in [0, {}]", SunLightDesc::max_angle_deg));
    }
}

}  // namespace

SceneDesc load_scene_desc(const std::string& path, bool confine_inputs) {
    if (is_gltf_file(path)) return load_gltf_scene_desc(path, confine_inputs);
    const InputFolder inputs = confine_inputs ? InputFolder::of_scene(path) : InputFolder{};
    const nlohmann::json root_json = parse_json_file(path);
    const JsonObject root(root_json, path, "");
    SceneDesc desc;
    desc.source_file = path;
    desc.name = root.string("name", fs::path(path).stem().string());
    check_scene_name(desc.name, path + ":/name");

    // A glTF file brings objects, materials, a camera and animations; the JSON adds to them.
    float gltf_duration_s = 0;
    bool has_camera = false;
    if (root.has("gltf")) gltf_duration_s = append_gltf(resolve_path(root, "gltf"), desc, has_camera, inputs);

    if (root.has("frames")) {
        const JsonObject frames = root.object("frames");
        if (frames.has("fps")) desc.fps_source = FpsSource::scene_file;
        desc.fps = frames.number("fps", desc.fps);
        if (!(desc.fps > 0)) frames.fail("fps", "must be positive");
        desc.frame_count = frames.integer("count", frames_covering(gltf_duration_s, desc.fps));
        if (desc.frame_count < 1) frames.fail("count", "must be at least 1");
        frames.warn_unread();
    } else if (gltf_duration_s > 0) {
        desc.frame_count = frames_covering(gltf_duration_s, desc.fps);
    }

    if (root.has("segments")) {
        for (const float start : root.numbers("segments")) {
            if (start != std::floor(start) || start < 0 || start >= float(desc.frame_count))
                root.fail("segments", "segment starts must be whole frame numbers within the animation");
            if (!desc.segment_starts.empty() && int(start) <= desc.segment_starts.back())
                root.fail("segments", "segment starts must increase");
            if (start > 0) desc.segment_starts.push_back(int(start));
        }
    }

    if (root.has("camera")) {
        desc.camera = parse_camera(root.object("camera"), desc.camera);
    } else if (!has_camera) {
        root.fail("camera", "missing required field (and no camera in the glTF file)");
    }

    std::map<std::string, int> material_index;
    for (size_t i = 0; i < desc.materials.size(); ++i) material_index[desc.materials[i].name] = int(i);
    if (root.has("materials")) {
        for (const auto& [name, json] : root.members("materials")) {
            material_index[name] = int(desc.materials.size());
            desc.materials.push_back(parse_material(name, json));
        }
    }
    if (root.has("objects")) {
        const std::vector<JsonObject> objects = root.objects("objects");
        const int black_material = int(desc.materials.size());
        desc.materials.push_back({.name = "(emitter)", .reflectance = {0, 0, 0}});
        for (size_t i = 0; i < objects.size(); ++i)
            desc.objects.push_back(parse_object(objects[i], material_index, black_material, inputs, int(i)));
    }
    if (root.has("lights"))
        for (const JsonObject& light : root.objects("lights")) {
            if (light.has("type") && light.string("type") == "sun")
                desc.suns.push_back(parse_sun_light(light));
            else
                desc.point_lights.push_back(parse_point_light(light));
        }
    if (root.has("sun_angles_degrees")) apply_sun_angles(root, desc);
    if (root.has("world")) desc.world = parse_world(root.object("world"), desc.suns, inputs);
    if (root.has("portals"))
        for (const JsonObject& portal : root.objects("portals")) desc.portals.push_back(parse_portal(portal));
    root.warn_unread();

    validate(desc);
    return desc;
}

bool has_distant_light(const SceneDesc& desc) {
    return std::any_of(desc.suns.begin(), desc.suns.end(),
                       [](const SunLightDesc& sun) { return !is_black(sun.irradiance); }) ||
           (desc.world && !desc.world->radiance->is_black());
}

}  // namespace steadylight
