#include "steadylight/base/transform.h"

#include <cmath>

namespace steadylight {

Quat Quat::from_axis_angle(Vec3 axis, float angle_rad) {
    const Vec3 a = normalize(axis) * std::sin(angle_rad / 2);
    return {a.x, a.y, a.z, std::cos(angle_rad / 2)};
}

Quat Quat::from_basis(Vec3 right, Vec3 up, Vec3 back) {
    // Shepperd's method on the rotation matrix whose columns are the basis vectors.
    const float m00 = right.x, m01 = up.x, m02 = back.x;
    const float m10 = right.y, m11 = up.y, m12 = back.y;
    const float m20 = right.z, m21 = up.z, m22 = back.z;
    const float trace = m00 + m11 + m22;
    Quat q;
    if (trace > 0) {
        const float s = std::sqrt(trace + 1) * 2;
        q = {(m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s, s / 4};
    } else if (m00 > m11 && m00 > m22) {
        const float s = std::sqrt(1 + m00 - m11 - m22) * 2;
        q = {s / 4, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s};
    } else if (m11 > m22) {
        const float s = std::sqrt(1 + m11 - m00 - m22) * 2;
        q = {(m01 + m10) / s, s / 4, (m12 + m21) / s, (m02 - m20) / s};
    } else {
        const float s = std::sqrt(1 + m22 - m00 - m11) * 2;
        q = {(m02 + m20) / s, (m12 + m21) / s, s / 4, (m10 - m01) / s};
    }
    return normalize(q);
}

Vec3 Quat::rotate(Vec3 v) const {
    const Vec3 u{x, y, z};
    return 2.0f * dot(u, v) * u + (w * w - dot(u, u)) * v + 2.0f * w * cross(u, v);
}

float dot(Quat a, Quat b) { return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w; }

Quat normalize(Quat q) {
    const float inv = 1.0f / std::sqrt(dot(q, q));
    return {q.x * inv, q.y * inv, q.z * inv, q.w * inv};
}

Quat operator*(Quat a, Quat b) {
    return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
            a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}

Quat slerp(Quat a, Quat b, float t) {
    float cos_theta = dot(a, b);
    // Take the shorter arc: q and -q are the same rotation.
    if (cos_theta < 0) {
        b = {-b.x, -b.y, -b.z, -b.w};
        cos_theta = -cos_theta;
    }
    float wa = 1 - t, wb = t;
    if (cos_theta < 0.9995f) {
        const float theta = std::acos(cos_theta);
        const float inv_sin = 1.0f / std::sin(theta);
        wa = std::sin((1 - t) * theta) * inv_sin;
        wb = std::sin(t * theta) * inv_sin;
    }
    return normalize({wa * a.x + wb * b.x, wa * a.y + wb * b.y, wa * a.z + wb * b.z, wa * a.w + wb * b.w});
}

Transform Transform::translate(Vec3 t) {
    Transform r;
    r.m[0][3] = t.x;
    r.m[1][3] = t.y;
    r.m[2][3] = t.z;
    return r;
}

Transform Transform::scale(Vec3 s) {
    Transform r;
    r.m[0][0] = s.x;
    r.m[1][1] = s.y;
    r.m[2][2] = s.z;
    return r;
}

Transform Transform::rotate(Quat q) {
    Transform r;
    const Vec3 cols[3] = {q.rotate({1, 0, 0}), q.rotate({0, 1, 0}), q.rotate({0, 0, 1})};
    for (int c = 0; c < 3; ++c)
        for (int row = 0; row < 3; ++row) r.m[row][c] = cols[c][row];
    return r;
}

Transform Transform::from_trs(Vec3 t, Quat r, Vec3 s) { return translate(t) * rotate(r) * scale(s); }

Vec3 Transform::point(Vec3 p) const { return vector(p) + Vec3{m[0][3], m[1][3], m[2][3]}; }

Vec3 Transform::vector(Vec3 v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

Vec3 Transform::normal(Vec3 n) const {
    // The cofactor matrix is the inverse transpose times the determinant: same direction,
    // no division, and well defined for any invertible transform.
    const Vec3 c0{m[0][0], m[1][0], m[2][0]}, c1{m[0][1], m[1][1], m[2][1]}, c2{m[0][2], m[1][2], m[2][2]};
    const Vec3 r0 = cross(c1, c2), r1 = cross(c2, c0), r2 = cross(c0, c1);
    const Vec3 result = r0 * n.x + r1 * n.y + r2 * n.z;
    return determinant() < 0 ? -result : result;
}

float Transform::determinant() const {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

Transform Transform::inverse() const {
    const float inv_det = 1.0f / determinant();
    Transform r;
    r.m[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) * inv_det;
    r.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * inv_det;
    r.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * inv_det;
    r.m[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) * inv_det;
    r.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * inv_det;
    r.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * inv_det;
    r.m[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) * inv_det;
    r.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * inv_det;
    r.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * inv_det;
    const Vec3 t = r.vector({m[0][3], m[1][3], m[2][3]});
    r.m[0][3] = -t.x;
    r.m[1][3] = -t.y;
    r.m[2][3] = -t.z;
    return r;
}

bool Transform::is_finite() const {
    for (const auto& row : m)
        for (const float v : row)
            if (!std::isfinite(v)) return false;
    return true;
}

Transform operator*(const Transform& a, const Transform& b) {
    Transform r;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 4; ++j) {
            r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j];
        }
        r.m[i][3] += a.m[i][3];
    }
    return r;
}

}  // namespace steadylight
