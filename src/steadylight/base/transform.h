// Rigid and scaled placements: unit quaternions for rotation, and affine transforms (3x4
// matrices) for world_from_object and friends. Compose as `a_from_b * b_from_c` (docs/style.md).
#pragma once

#include "steadylight/base/vec.h"

namespace steadylight {

/// A rotation quaternion (x, y, z, w), w the real part, as in glTF.
struct Quat {
    float x = 0, y = 0, z = 0, w = 1;

    static Quat from_axis_angle(Vec3 axis, float angle_rad);
    /// The rotation taking the camera's local axes (right +x, up +y, looking down -z) onto `right`,
    /// `up`, `-forward`; the three vectors must be orthonormal.
    static Quat from_basis(Vec3 right, Vec3 up, Vec3 back);
    Vec3 rotate(Vec3 v) const;
    bool operator==(const Quat&) const = default;
};

float dot(Quat a, Quat b);
Quat normalize(Quat q);
Quat operator*(Quat a, Quat b);
/// Shortest-arc spherical linear interpolation between two unit quaternions.
Quat slerp(Quat a, Quat b, float t);

/// An affine transform: p' = m * p + t, stored as three rows of four.
struct Transform {
    float m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};

    static Transform translate(Vec3 t);
    static Transform scale(Vec3 s);
    static Transform rotate(Quat q);
    /// Translation * rotation * scale, the glTF node order.
    static Transform from_trs(Vec3 t, Quat r, Vec3 s);

    Vec3 point(Vec3 p) const;
    Vec3 vector(Vec3 v) const;
    /// Transforms a normal by the inverse transpose; the result is not normalised.
    Vec3 normal(Vec3 n) const;
    Transform inverse() const;
    float determinant() const;
    bool is_finite() const;
    bool operator==(const Transform&) const = default;
};

Transform operator*(const Transform& a, const Transform& b);

}  // namespace steadylight
