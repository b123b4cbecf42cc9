// Sampling a rectangular light by the solid angle it covers (Ureña, Fajardo and King 2013, "An
// Area-Preserving Parametrization for Spherical Rectangles"), for the direct light of points
// close to it: sampling by area puts most samples where the light is seen at a grazing angle or
// from far away, and a point near a large panel then gets noisy light. Every sample here counts
// the same (pdf = 1 / solid angle). The map from the unit square is continuous, so stratified
// numbers stay stratified on the light.
#pragma once

#include <optional>

#include "steadylight/base/vec.h"

namespace steadylight {

/// corner + s edge_u + t edge_v for s, t in [0, 1]; edge_u and edge_v at right angles.
struct Rectangle {
    Vec3 corner, edge_u, edge_v;
};

/// The rectangle two triangles make together, when they make one (within rounding): they share
/// an edge and their other corners complete a parallelogram with right angles.
std::optional<Rectangle> rectangle_of(const Vec3 (&a)[3], const Vec3 (&b)[3]);

/// A rectangle as seen from a point.
class SphericalRectangle {
public:
    SphericalRectangle(const Rectangle& rectangle, Vec3 from);

    /// Steradians; 0 when the point lies in the rectangle's plane.
    float solid_angle() const { return m_solid_angle; }
    /// The point of the rectangle in direction u (u uniform on the unit square: uniform in
    /// solid angle).
    Vec3 sample(Vec2 u) const;

private:
    Vec3 m_from, m_x, m_y, m_z;  // the local frame: x along edge_u, y along edge_v, z towards the point's side
    float m_x0 = 0, m_x1 = 0, m_y0 = 0, m_y1 = 0, m_z0 = 0;
    float m_b0 = 0, m_b1 = 0, m_k = 0;
    float m_solid_angle = 0;
};

}  // namespace steadylight
