// Spherical rectangles (spherical_rectangle.h), after Ureña, Fajardo and King 2013, §3-4.
#include "steadylight/shading/spherical_rectangle.h"

#include <algorithm>
#include <cmath>

namespace steadylight {

std::optional<Rectangle> rectangle_of(const Vec3 (&a)[3], const Vec3 (&b)[3]) {
    // The corners of a that b shares, and the one each has alone.
    int shared = 0;
    Vec3 only_a, only_b, common[2];
    for (const Vec3& p : a) {
        const bool in_b = std::any_of(std::begin(b), std::end(b), [&](const Vec3& q) { return p == q; });
        if (in_b && shared < 2) common[shared++] = p;
        if (!in_b) only_a = p;
    }
    if (shared != 2) return std::nullopt;
    for (const Vec3& q : b)
        if (!(q == common[0]) && !(q == common[1])) only_b = q;
    const Vec3 edge_u = common[0] - only_a, edge_v = common[1] - only_a;
    const float scale = std::max(length2(edge_u), length2(edge_v));
    if (!(scale > 0)) return std::nullopt;
    const bool parallelogram = length2(only_a + edge_u + edge_v - only_b) <= 1e-8f * scale;
    const bool right_angled = std::abs(dot(edge_u, edge_v)) <= 1e-4f * scale;
    if (!parallelogram || !right_angled) return std::nullopt;
    return Rectangle{only_a, edge_u, edge_v};
}

SphericalRectangle::SphericalRectangle(const Rectangle& rectangle, Vec3 from) : m_from(from) {
    const float length_u = length(rectangle.edge_u), length_v = length(rectangle.edge_v);
    m_x = rectangle.edge_u / length_u;
    m_y = rectangle.edge_v / length_v;
    m_z = cross(m_x, m_y);
    const Vec3 d = rectangle.corner - from;
    m_z0 = dot(d, m_z);
    if (m_z0 > 0) m_z = -m_z, m_z0 = -m_z0;  // z points from the rectangle towards `from`
    m_x0 = dot(d, m_x), m_y0 = dot(d, m_y);
    m_x1 = m_x0 + length_u, m_y1 = m_y0 + length_v;
    if (!(m_z0 < 0)) return;  // in the plane: no solid angle
    // The corners as seen from `from`, the normals of the planes through it and each edge, and
    // the angles between them.
    const Vec3 v00{m_x0, m_y0, m_z0}, v01{m_x0, m_y1, m_z0}, v10{m_x1, m_y0, m_z0}, v11{m_x1, m_y1, m_z0};
    const Vec3 n0 = normalize(cross(v00, v10)), n1 = normalize(cross(v10, v11));
    const Vec3 n2 = normalize(cross(v11, v01)), n3 = normalize(cross(v01, v00));
    const auto angle = [](Vec3 p, Vec3 q) { return std::acos(std::clamp(-dot(p, q), -1.0f, 1.0f)); };
    const float g0 = angle(n0, n1), g1 = angle(n1, n2), g2 = angle(n2, n3), g3 = angle(n3, n0);
    m_b0 = n0.z, m_b1 = n2.z;
    m_k = 2 * pi - g2 - g3;
    m_solid_angle = std::max(g0 + g1 - m_k, 0.0f);
}

Vec3 SphericalRectangle::sample(Vec2 u) const {
    // u.x picks the angle of the sub-rectangle [x0, xu], hence xu; u.y the height along y.
    const float au = u.x * m_solid_angle + m_k;
    const float fu = (std::cos(au) * m_b0 - m_b1) / std::sin(au);
    const float cu = std::clamp(std::copysign(1.0f, fu) / std::sqrt(fu * fu + m_b0 * m_b0), -1.0f, 1.0f);
    const float xu = std::clamp(-(cu * m_z0) / std::max(std::sqrt(1 - cu * cu), 1e-7f), m_x0, m_x1);
    const float d = std::sqrt(xu * xu + m_z0 * m_z0);
    const float h0 = m_y0 / std::sqrt(d * d + m_y0 * m_y0), h1 = m_y1 / std::sqrt(d * d + m_y1 * m_y1);
    const float hv = h0 + u.y * (h1 - h0), hv2 = hv * hv;
    const float yv = hv2 < 1 - 1e-6f ? std::clamp(hv * d / std::sqrt(1 - hv2), m_y0, m_y1) : m_y1;
    return m_from + m_x * xu + m_y * yv + m_z * m_z0;
}

}  // namespace steadylight
