#include "steadylight/scene/scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <variant>

namespace steadylight {

Ray Camera::generate_ray(float x, float y) const {
    const float aspect = float(width) / float(height);
    const Vec3 d_camera{(2 * x / float(width) - 1) * tan_half_fov_y * aspect,
                        (1 - 2 * y / float(height)) * tan_half_fov_y, -1};
    return {world_from_camera.point({}), normalize(world_from_camera.vector(d_camera)), infinity};
}

std::optional<Vec2> Camera::project(Vec3 p) const {
    const Vec3 q = world_from_camera.inverse().point(p);
    if (!(q.z < 0)) return std::nullopt;
    const float aspect = float(width) / float(height);
    const float sx = q.x / (-q.z * tan_half_fov_y * aspect), sy = q.y / (-q.z * tan_half_fov_y);
    return Vec2{(sx + 1) / 2 * float(width), (1 - sy) / 2 * float(height)};
}

namespace {

/// Sets the lights of `state`: emissions, lamps and suns at `time_s`.
void evaluate_lights(const SceneDesc& desc, float time_s, FrameState& state) {
    state.emission.reserve(desc.objects.size());
    for (const ObjectDesc& object : desc.objects) state.emission.push_back(object.emission_at(time_s));
    state.point_lights.reserve(desc.point_lights.size());
    for (const PointLightDesc& light : desc.point_lights) state.point_lights.push_back(light.pose_at(time_s));
    state.sun_directions.reserve(desc.suns.size());
    for (const SunLightDesc& sun : desc.suns) state.sun_directions.push_back(sun.direction_at(time_s));
}

/// True when some light at `frame` is switched or dimmed from the frame before.
bool lights_change_at(const SceneDesc& desc, int frame) {
    FrameState before, now;
    evaluate_lights(desc, desc.frame_time_s(frame - 1), before);
    evaluate_lights(desc, desc.frame_time_s(frame), now);
    return !now.same_light_levels(before);
}

std::vector<Segment> split_into_segments(const SceneDesc& desc) {
    const bool resized_light = std::any_of(desc.objects.begin(), desc.objects.end(), [](const ObjectDesc& o) {
        return o.is_emitter() && o.is_dynamic() && !o.is_moving_light();
    });
    std::vector<int> starts{0};
    for (int frame = 1; frame < desc.frame_count; ++frame)
        if (resized_light || std::count(desc.segment_starts.begin(), desc.segment_starts.end(), frame) ||
            lights_change_at(desc, frame))
            starts.push_back(frame);
    std::vector<Segment> segments;
    for (size_t i = 0; i < starts.size(); ++i)
        segments.push_back({starts[i], i + 1 < starts.size() ? starts[i + 1] - 1 : desc.frame_count - 1});
    return segments;
}

/// The corners of an object's box in its own space.
std::array<Vec3, 8> object_box_corners(const Geometry& geometry) {
    Vec3 lo{infinity, infinity, infinity}, hi = -lo;
    if (const auto* mesh = std::get_if<TriangleMesh>(&geometry)) {
        for (const Vec3 p : mesh->positions) lo = min(lo, p), hi = max(hi, p);
    } else {
        const Sphere& sphere = std::get<Sphere>(geometry);
        const Vec3 r{sphere.radius, sphere.radius, sphere.radius};
        lo = sphere.center - r, hi = sphere.center + r;
    }
    std::array<Vec3, 8> corners;
    for (int i = 0; i < 8; ++i) corners[size_t(i)] = {i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z};
    return corners;
}

/// Scene::bounds(): a sphere about the box of every object's box at every frame (a static
/// object's once).
BoundingSphere animation_bounds(const SceneDesc& desc) {
    Vec3 lo{infinity, infinity, infinity}, hi = -lo;
    for (const ObjectDesc& object : desc.objects) {
        const std::array<Vec3, 8> corners = object_box_corners(object.geometry);
        const int frames = is_chain_animated(object.placement) ? desc.frame_count : 1;
        for (int frame = 0; frame < frames; ++frame) {
            const Transform world_from_object = evaluate_chain(object.placement, desc.frame_time_s(frame));
            for (const Vec3 corner : corners) {
                const Vec3 p = world_from_object.point(corner);
                lo = min(lo, p), hi = max(hi, p);
            }
        }
    }
    return BoundingSphere::of_box(lo, hi);
}

}  // namespace

Scene::Scene(SceneDesc desc) : m_desc(std::move(desc)) {
    validate(m_desc);
    for (int i = 0; i < int(m_desc.objects.size()); ++i)
        (m_desc.objects[size_t(i)].is_dynamic() ? m_dynamic : m_static).push_back(i);
    m_segments = split_into_segments(m_desc);
    m_bounds = animation_bounds(m_desc);
}

const Segment& Scene::segment_of(int frame) const {
    for (const Segment& segment : m_segments)
        if (frame <= segment.last) return segment;
    return m_segments.back();
}

void Scene::set_resolution(int width, int height) {
    m_desc.camera.width = width;
    m_desc.camera.height = height;
}

FrameState Scene::evaluate(int frame) const {
    FrameState state;
    state.frame = frame;
    state.time_s = m_desc.frame_time_s(frame);
    state.camera.world_from_camera = evaluate_chain(m_desc.camera.placement, state.time_s);
    state.camera.tan_half_fov_y = std::tan(m_desc.camera.fov_y_deg * pi / 360);
    state.camera.width = m_desc.camera.width;
    state.camera.height = m_desc.camera.height;
    state.camera.transparent_background = m_desc.camera.transparent_background;
    state.world_from_object.reserve(m_desc.objects.size());
    for (const ObjectDesc& object : m_desc.objects)
        state.world_from_object.push_back(evaluate_chain(object.placement, state.time_s));
    evaluate_lights(m_desc, state.time_s, state);
    return state;
}

}  // namespace steadylight
