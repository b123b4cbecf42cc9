#include "steadylight/scene/scene.h"

#include <cmath>

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

Scene::Scene(SceneDesc desc) : m_desc(std::move(desc)) {
    validate(m_desc);
    for (int i = 0; i < int(m_desc.objects.size()); ++i)
        (m_desc.objects[size_t(i)].is_dynamic() ? m_dynamic : m_static).push_back(i);
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
    state.world_from_object.reserve(m_desc.objects.size());
    for (const ObjectDesc& object : m_desc.objects)
        state.world_from_object.push_back(evaluate_chain(object.placement, state.time_s));
    return state;
}

}  // namespace steadylight
