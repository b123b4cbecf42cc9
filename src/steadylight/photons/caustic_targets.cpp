#include "steadylight/photons/caustic_targets.h"

#include <algorithm>
#include <cmath>

#include "steadylight/base/sampling.h"

namespace steadylight {

std::pair<Vec3, float> bounding_sphere(const Scene& scene, const FrameState& frame, int object) {
    const Transform& world_from_object = frame.world_from_object[size_t(object)];
    const Geometry& geometry = scene.object(object).geometry;
    if (const auto* sphere = std::get_if<Sphere>(&geometry)) {
        float scale = 0;
        for (const Vec3 axis : {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}})
            scale = std::max(scale, length(world_from_object.vector(axis)));
        return {world_from_object.point(sphere->center), sphere->radius * scale};
    }
    const TriangleMesh& mesh = std::get<TriangleMesh>(geometry);
    Vec3 lo{INFINITY, INFINITY, INFINITY}, hi = -lo;
    for (const Vec3 p : mesh.positions) {
        const Vec3 w = world_from_object.point(p);
        lo = min(lo, w), hi = max(hi, w);
    }
    const Vec3 center = (lo + hi) * 0.5f;
    float radius = 0;
    for (const Vec3 p : mesh.positions) radius = std::max(radius, length(world_from_object.point(p) - center));
    return {center, radius * 1.0001f};  // rounding
}

CausticTargets::CausticTargets(const FrameContext& context, Visibility visibility) {
    const Scene& scene = context.scene;
    for (int object = 0; object < int(scene.objects().size()); ++object) {
        if (context.bsdf_of(object).is_diffuse()) continue;
        if (visibility == Visibility::static_only && scene.object(object).is_dynamic()) continue;
        const auto [center, radius] = bounding_sphere(scene, context.frame, object);
        m_centers.push_back(center);
        m_radii.push_back(radius);
    }
    if (m_centers.size() > max_targets) m_centers.clear(), m_radii.clear();
}

float CausticTargets::cones_from(Vec3 p, Cones& cones) const {
    float total = 0;
    for (size_t i = 0; i < m_centers.size(); ++i) {
        const Vec3 d = m_centers[i] - p;
        const float distance2 = length2(d), radius2 = m_radii[i] * m_radii[i];
        if (distance2 <= radius2) return 0;  // inside a target: it is seen every way
        const float distance = std::sqrt(distance2);
        const float sin2 = radius2 / distance2;
        const float cos_max = std::sqrt(1 - sin2);
        // 1 - cos_max without cancellation for small, far targets.
        cones[i] = {d / distance, cos_max, 2 * pi * sin2 / (1 + cos_max)};
        total += cones[i].solid_angle;
    }
    // Beyond a hemisphere aiming cannot beat the light's own cosine-weighted emission.
    return total < 2 * pi ? total : 0;
}

std::optional<AimedDirection> CausticTargets::sample(Vec3 p, Vec2 u) const {
    if (m_centers.empty()) return std::nullopt;
    Cones cones;
    const float total = cones_from(p, cones);
    if (!(total > 0)) return std::nullopt;
    // Choose a cone with u.x in proportion to its solid angle, then reuse the rest of u.x in it.
    const size_t n = m_centers.size();
    size_t chosen = 0;
    float lo = 0;
    while (chosen + 1 < n && u.x >= lo + cones[chosen].solid_angle / total) lo += cones[chosen++].solid_angle / total;
    const float share = cones[chosen].solid_angle / total;
    u.x = std::clamp((u.x - lo) / share, 0.0f, 0x1.fffffep-1f);
    const Cone& cone = cones[chosen];
    const Vec3 d = normalize(OrthonormalBasis::from_normal(cone.axis).to_world(sample_uniform_cone(u, cone.cos_max)));
    // At least the chosen cone holds d, whatever rounding says at its rim.
    return AimedDirection{d, std::max(1, cones_holding(cones, d)) / total};
}

float CausticTargets::pdf(Vec3 p, Vec3 d) const {
    if (m_centers.empty()) return 0;
    Cones cones;
    const float total = cones_from(p, cones);
    return total > 0 ? float(cones_holding(cones, d)) / total : 0;
}

int CausticTargets::cones_holding(const Cones& cones, Vec3 d) const {
    int holding = 0;
    for (size_t i = 0; i < m_centers.size(); ++i) holding += dot(d, cones[i].axis) >= cones[i].cos_max;
    return holding;
}

}  // namespace steadylight
