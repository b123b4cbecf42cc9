// Spherical rectangles (spherical_rectangle.h): the solid angle, and samples uniform in it.
#include "steadylight/shading/spherical_rectangle.h"

#include <gtest/gtest.h>

#include "steadylight/base/rng.h"
#include "steadylight/scene/shapes.h"

namespace steadylight {
namespace {

const Rectangle panel{{-0.5f, -0.3f, 1}, {1.5f, 0, 0}, {0, 0.8f, 0}};

/// The solid angle of `r` seen from `from`, by summing cos / d^2 over a fine grid on it.
double solid_angle_by_area(const Rectangle& r, Vec3 from, int n = 400) {
    const Vec3 normal = normalize(cross(r.edge_u, r.edge_v));
    const double cell = length(r.edge_u) * length(r.edge_v) / (double(n) * n);
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const Vec3 d = r.corner + r.edge_u * ((i + 0.5f) / n) + r.edge_v * ((j + 0.5f) / n) - from;
            const double d2 = length2(d);
            sum += std::abs(dot(d, normal)) / std::sqrt(d2) / d2 * cell;
        }
    return sum;
}

TEST(SphericalRectangle, SolidAngleMatchesTheIntegralOverTheRectangle) {
    for (const Vec3 from : {Vec3{0, 0, 0}, Vec3{0.2f, 0.1f, 0.9f}, Vec3{3, -2, -1}, Vec3{0.1f, 0.1f, 2}}) {
        const double expected = solid_angle_by_area(panel, from);
        EXPECT_NEAR(SphericalRectangle(panel, from).solid_angle(), expected, 2e-3 * expected) << to_string(from);
    }
    EXPECT_EQ(SphericalRectangle(panel, {5, 5, 1}).solid_angle(), 0.0f);  // in its plane
}

// The share of samples that land in a part of the rectangle is that part's share of the solid
// angle, and every sample lies on the rectangle.
TEST(SphericalRectangle, SamplesAreUniformInSolidAngle) {
    const Rectangle part{panel.corner, panel.edge_u * 0.3f, panel.edge_v * 0.6f};
    for (const Vec3 from : {Vec3{0, 0, 0}, Vec3{0.2f, 0.1f, 0.9f}, Vec3{-1, 1, 2.5f}}) {
        const SphericalRectangle seen(panel, from);
        const double expected = SphericalRectangle(part, from).solid_angle() / seen.solid_angle();
        Pcg32 rng(4);
        const int n = 200'000;
        int inside = 0;
        for (int i = 0; i < n; ++i) {
            const Vec3 p = seen.sample(rng.next_vec2()) - panel.corner;
            const float s = dot(p, panel.edge_u) / length2(panel.edge_u),
                        t = dot(p, panel.edge_v) / length2(panel.edge_v);
            ASSERT_TRUE(s >= -1e-4f && s <= 1 + 1e-4f && t >= -1e-4f && t <= 1 + 1e-4f) << s << " " << t;
            ASSERT_NEAR(dot(p, normalize(cross(panel.edge_u, panel.edge_v))), 0, 1e-4f);
            inside += s <= 0.3f && t <= 0.6f;
        }
        EXPECT_NEAR(double(inside) / n, expected, 0.005) << to_string(from);
    }
}

TEST(SphericalRectangle, TwoTrianglesOfAQuadAreARectangleAndASkewedPairIsNot) {
    const TriangleMesh quad = make_quad(panel.corner, panel.edge_u, panel.edge_v);
    ASSERT_EQ(quad.indices.size(), 6u);
    const auto corner = [&](size_t i) { return quad.positions[size_t(quad.indices[i])]; };
    const Vec3 a[3] = {corner(0), corner(1), corner(2)}, b[3] = {corner(3), corner(4), corner(5)};
    const std::optional<Rectangle> r = rectangle_of(a, b);
    ASSERT_TRUE(r);
    EXPECT_NEAR(length(r->edge_u) * length(r->edge_v), 1.5f * 0.8f, 1e-5f);
    const Vec3 skew_a[3] = {{0, 0, 0}, {1, 0, 0}, {1.5f, 1, 0}}, skew_b[3] = {{0, 0, 0}, {1.5f, 1, 0}, {0.5f, 1, 0}};
    EXPECT_FALSE(rectangle_of(skew_a, skew_b));
}

}  // namespace
}  // namespace steadylight
