// SceneDesc: the scene as the user described it, loaded from JSON (docs/scene-format.md), from
// glTF 2.0 or from both. It is plain data with every mesh already read into memory; Scene
// (scene.h) prepares it for rendering. This is the first stage of the pipeline (docs/design.md).
#pragma once

#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "steadylight/base/color.h"
#include "steadylight/base/input_file.h"
#include "steadylight/scene/animation.h"
#include "steadylight/scene/environment_map.h"
#include "steadylight/scene/texture.h"

namespace steadylight {

/// `pbr` is glTF's metallic-roughness model (docs/materials.md): a GGX conductor tinted by the
/// base colour where metallic, and a diffuse base under a GGX dielectric coat where not.
enum class MaterialType { lambert, mirror, dielectric, glossy, pbr };

/// glTF's alpha modes (§3.9.4): `mask` cuts out where alpha < alpha_cutoff, for every ray;
/// `blend` is treated as a mask at the same cutoff (docs/gltf.md).
enum class AlphaMode { opaque, mask, blend };

struct MaterialDesc {
    std::string name;
    MaterialType type = MaterialType::lambert;
    Rgb reflectance{0.8f, 0.8f, 0.8f};  // lambert albedo; mirror and glossy: normal-incidence colour; pbr: base colour
    Rgb transmittance{1, 1, 1};         // dielectric: colour filter on refraction
    float ior = 1.5f;                   // dielectric: index of refraction inside / outside; pbr: the coat's
    float roughness = 0.3f;             // glossy, pbr and dielectric: GGX alpha = roughness^2 (dielectric: 0 is smooth)
    // dielectric: Beer-Lambert absorption inside (KHR_materials_volume): light that travels
    // attenuation_distance (scene units) inside keeps attenuation_color of itself.
    Rgb attenuation_color{1, 1, 1};
    float attenuation_distance = std::numeric_limits<float>::infinity();
    float metallic = 0;        // pbr: 1 conductor, 0 coated diffuse (blended between)
    float specular = 1;        // pbr: scales the coat's Fresnel (KHR_materials_specular); 0: no coat
    float specular_color = 1;  // pbr: scales the coat's normal-incidence Fresnel only
    float alpha = 1;           // base colour alpha
    AlphaMode alpha_mode = AlphaMode::opaque;
    float alpha_cutoff = 0.5f;
    TextureRef base_color_texture;          // sRGB; multiplies `reflectance` and `alpha`
    TextureRef metallic_roughness_texture;  // linear; B multiplies metallic, G roughness
    TextureRef normal_texture;              // tangent-space normal map
    float normal_scale = 1;                 // scales the map's x and y
    TextureRef emissive_texture;            // sRGB; multiplies the emission of objects using it

    bool is_textured() const {
        return base_color_texture.is_set() || metallic_roughness_texture.is_set() || normal_texture.is_set();
    }
    bool has_cutouts() const { return alpha_mode != AlphaMode::opaque; }
    /// The absorption coefficient sigma_a = -ln(attenuation_color) / attenuation_distance per
    /// scene unit; black when the material absorbs nothing (not a dielectric, or no volume).
    Rgb absorption() const;
};

/// Triangles in object space. Every per-vertex array is empty or one per position.
struct TriangleMesh {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;   // empty: flat shading
    std::vector<int> indices;    // three per triangle, counter-clockwise around the front normal
    std::vector<Vec2> uv0, uv1;  // TEXCOORD_0 and _1
    std::vector<Rgba> colors;    // COLOR_0, multiplying the base colour and alpha
    std::vector<Rgba> tangents;  // xyz unit tangent, w = +-1 bitangent sign (glTF TANGENT)
};

/// An analytic sphere in object space; the front side is the outside.
struct Sphere {
    Vec3 center;
    float radius = 1;
};

using Geometry = std::variant<TriangleMesh, Sphere>;

/// True when some key of `track` is not black: the light it drives is on at some time.
bool is_ever_lit(const Track<Rgb>& track);

struct ObjectDesc {
    std::string name;
    Geometry geometry;
    int material = 0;                          // index into SceneDesc::materials
    Rgb emission;                              // radiance leaving the front side; black when not a light
    std::optional<Track<Rgb>> emission_track;  // when set, replaces `emission` (lights switched or dimmed)
    bool two_sided_emission = false;
    std::vector<AnimatedTrs> placement;  // world_from_object = product, parent first
    bool marked_dynamic = false;         // "dynamic": true in the file, even when not animated

    /// The radiance leaving the front side at `time_s`.
    Rgb emission_at(float time_s) const { return emission_track ? emission_track->evaluate(time_s) : emission; }
    /// True when the object emits at some time: it is an area light (off where its emission is black).
    bool is_emitter() const { return emission_track ? is_ever_lit(*emission_track) : !is_black(emission); }
    bool is_emission_animated() const { return emission_track && !emission_track->is_constant(); }
    /// Moving, or marked dynamic. Emission that changes does not count: within a segment it is
    /// constant (segments split where it changes), so it lights the static scene (docs/design.md).
    bool is_dynamic() const { return marked_dynamic || is_chain_animated(placement); }
    /// A dynamic emitter whose size stays: lit apart from the static pass, as a lamp that moves is
    /// (PhotonGroup::moving). One whose size changes changes its power: every frame is then a
    /// segment of its own.
    bool is_moving_light() const { return is_emitter() && is_dynamic() && !is_chain_scaled(placement); }
};

enum class PointLightType { point, spot };

/// A point or spot light as it is at one time: where it is, where it points, how bright.
struct PointLightPose {
    Vec3 position;
    Vec3 direction;  // unit
    Rgb intensity;

    bool operator==(const PointLightPose&) const = default;
};

/// A light with no area: radiant intensity (W/sr per channel) from one point; a spot light
/// restricts it to a cone, fading out between `falloff_start_deg` and `cone_angle_deg`.
/// `position` and `direction` are in the light's own space, which `placement` puts in the world
/// (a glTF node and its ancestors; a JSON light's translation and rotation tracks): a lamp that
/// moves when the placement is animated.
struct PointLightDesc {
    std::string name;
    PointLightType type = PointLightType::point;
    Vec3 position;
    Vec3 direction{0, -1, 0};
    Rgb intensity;
    std::optional<Track<Rgb>> intensity_track;  // when set, replaces `intensity`
    float cone_angle_deg = 30;
    float falloff_start_deg = 25;
    std::vector<AnimatedTrs> placement;  // world_from_light, parent first; empty: the identity

    /// The radiant intensity at `time_s`.
    Rgb intensity_at(float time_s) const { return intensity_track ? intensity_track->evaluate(time_s) : intensity; }
    bool is_intensity_animated() const { return intensity_track && !intensity_track->is_constant(); }
    bool is_moving() const { return is_chain_animated(placement); }
    /// Where the light is, where it points and its intensity at `time_s`.
    PointLightPose pose_at(float time_s) const;
};

/// The sun, or any light so far away that its rays arrive parallel: `irradiance` (W/m² per
/// channel) on a surface facing it, arriving within a cone of angular diameter `angle_deg` about
/// `direction`, the unit direction the light travels (0: a hard shadow's delta light).
/// `direction` is in the sun's own space, which `placement` turns in the world (a glTF node and
/// its ancestors; a JSON sun's rotation track): a sun that crosses the sky when it is animated.
struct SunLightDesc {
    std::string name;
    Vec3 direction{0, -1, 0};
    Rgb irradiance;
    float angle_deg = default_sun_angle_deg;
    std::vector<AnimatedTrs> placement;  // world_from_sun, parent first; empty: the identity

    bool is_moving() const { return is_chain_animated(placement); }
    /// The unit direction the light travels at `time_s`.
    Vec3 direction_at(float time_s) const;

    static constexpr float default_sun_angle_deg = 0.53f;  // the real sun's
    static constexpr float max_angle_deg = 90;
};

/// Light from far away in every direction (Blender's World): its radiance over directions, in
/// the units of an emitter's radiance (Blender's Background shader): a uniform colour, an
/// equirectangular image, or Blender's Nishita sky (whose sun disc is one of SceneDesc::suns).
struct WorldDesc {
    std::shared_ptr<const EnvironmentMap> radiance;  // never null
    std::string description;                         // what it is, for `steadylight info`

    /// A world of uniform radiance `radiance` (finite, not negative).
    static WorldDesc uniform(Rgb radiance);

    static constexpr float max_strength = 1e6f;
    static constexpr int sky_image_width = 1024;  // the Nishita sky's image: 1024 x 512
};

/// A window of an interior lit from outside, as Cycles' light portals mark them: the quad
/// corner + s edge_u + t edge_v (s, t in [0, 1]), edge_u × edge_v facing into the room. Light
/// from far away (suns and the world) aims its photons through the portals, and the world's
/// direct light at points inside samples them too.
struct PortalDesc {
    Vec3 corner, edge_u, edge_v;

    Vec3 inward_normal() const { return normalize(cross(edge_u, edge_v)); }
    float area() const { return length(cross(edge_u, edge_v)); }
};

/// A pinhole camera looking down its local -z with +y up (the glTF convention).
struct CameraDesc {
    std::vector<AnimatedTrs> placement;  // world_from_camera
    float fov_y_deg = 40;
    int width = 320;
    int height = 240;
    /// The film's background: the world the camera sees directly is left out (alpha 0, as
    /// Blender's Film > Transparent); set from --transparent-background, never from a scene file.
    bool transparent_background = false;
};

/// Where SceneDesc::fps came from, as `steadylight info` says it.
enum class FpsSource {
    default_rate,  // nothing set it: 24 fps
    scene_file,    // "frames": {"fps": ...} in the JSON scene
    gltf_keys,     // the key spacing of a sampled glTF animation (gltf_animation.h)
};

struct SceneDesc {
    std::string name;         // used in output file names
    std::string source_file;  // where it was loaded from, for messages
    CameraDesc camera;
    std::vector<MaterialDesc> materials;
    std::vector<TextureImage> images;  // what MaterialDesc's TextureRefs point at
    std::vector<ObjectDesc> objects;
    std::vector<PointLightDesc> point_lights;
    std::vector<SunLightDesc> suns;
    std::optional<WorldDesc> world;
    std::vector<PortalDesc> portals;
    int frame_count = 1;
    float fps = 24;
    FpsSource fps_source = FpsSource::default_rate;
    std::vector<int> segment_starts;  // frames where the scene file starts a new segment (besides 0)

    float frame_time_s(int frame) const { return float(frame) / fps; }
};

/// Loads a JSON scene (docs/scene-format.md), or a .gltf/.glb file as a whole scene
/// (docs/gltf.md); relative paths are relative to the file. With `confine_inputs`, every file
/// the scene refers to must lie inside the scene file's folder (base/input_file.h InputFolder).
/// Throws InputError naming the file and the JSON pointer of anything wrong.
SceneDesc load_scene_desc(const std::string& path, bool confine_inputs = false);

/// Where `desc.fps` came from, for `steadylight info`: "default", "from the scene file" or
/// "from the glTF keys, one every 1/39 s".
std::string describe_fps_source(const SceneDesc& desc);

/// The most frames a scene may have: every frame's transforms are checked, and frame lists are
/// kept in memory.
constexpr int max_frame_count = 1000000;

/// The longest scene name. The name starts every file a run writes into its output folder, and
/// the longest of those must fit the file-name limit (255 bytes): a frame claim's temporary file,
/// `<name>_<frame>.claim.<host>-<pid>.tmp`, adds at most 91 bytes (7 frame digits, a 64-byte host
/// name, a 7-digit pid); the others fewer (`<name>_<frame>.dynamic_records.png.partial`: 36).
constexpr size_t max_scene_name_bytes = 128;

/// Throws InputError naming `where` when `name` cannot be a scene's name: empty, `.` or `..`,
/// holding a path separator, a control character or a NUL, or longer than max_scene_name_bytes.
/// Output paths are made from it, so that nothing is written outside the output folder; the
/// loaders check the name a file gives (or the file's own name).
void check_scene_name(const std::string& name, const std::string& where);

/// Checks what no single loader can: indices in range, finite numbers, emitters with area,
/// well-formed emission and intensity tracks.
void validate(const SceneDesc& desc);

/// True when the scene has a sun or a world that sends light.
bool has_distant_light(const SceneDesc& desc);

}  // namespace steadylight
