#include "steadylight/base/transform.h"

#include <gtest/gtest.h>

namespace steadylight {
namespace {

void expect_near(Vec3 a, Vec3 b, float tolerance = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(Transform, IdentityLeavesPointsAlone) { expect_near(Transform{}.point({1, 2, 3}), {1, 2, 3}); }

TEST(Transform, QuaternionRotatesCounterClockwiseAboutItsAxis) {
    const Quat q = Quat::from_axis_angle({0, 1, 0}, pi / 2);
    // +90 degrees about +y takes +x to -z (right-handed).
    expect_near(q.rotate({1, 0, 0}), {0, 0, -1});
    expect_near(Transform::rotate(q).point({1, 0, 0}), {0, 0, -1});
}

TEST(Transform, TrsAppliesScaleThenRotationThenTranslation) {
    const Transform t = Transform::from_trs({1, 0, 0}, Quat::from_axis_angle({0, 0, 1}, pi / 2), {2, 2, 2});
    expect_near(t.point({1, 0, 0}), {1, 2, 0});
}

TEST(Transform, InverseUndoesTheTransform) {
    const Transform t = Transform::from_trs({1, -2, 3}, Quat::from_axis_angle({1, 1, 0}, 0.7f), {2, 0.5f, 3});
    expect_near(t.inverse().point(t.point({0.3f, 0.2f, -0.9f})), {0.3f, 0.2f, -0.9f}, 1e-4f);
}

TEST(Transform, NormalsStayPerpendicularUnderNonUniformScale) {
    const Transform t = Transform::from_trs({}, Quat::from_axis_angle({0, 0, 1}, 0.3f), {4, 1, 1});
    const Vec3 tangent{1, -1, 0}, n{1, 1, 0};
    EXPECT_NEAR(dot(t.vector(tangent), t.normal(n)), 0, 1e-4f);
}

TEST(Transform, SlerpHalfwayIsHalfTheAngle) {
    const Quat a{}, b = Quat::from_axis_angle({0, 0, 1}, pi / 2);
    expect_near(slerp(a, b, 0.5f).rotate({1, 0, 0}), normalize(Vec3{1, 1, 0}));
}

TEST(Transform, SlerpTakesTheShorterArc) {
    const Quat a = Quat::from_axis_angle({0, 0, 1}, 0.1f);
    const Quat b = Quat::from_axis_angle({0, 0, 1}, -0.1f);
    const Quat neg_b{-b.x, -b.y, -b.z, -b.w};
    expect_near(slerp(a, neg_b, 0.5f).rotate({1, 0, 0}), {1, 0, 0});
}

TEST(Transform, BasisRoundTripsThroughAQuaternion) {
    const Vec3 right = normalize(Vec3{1, 0, 1}), up{0, 1, 0}, back = cross(right, up);
    const Quat q = Quat::from_basis(right, up, back);
    expect_near(q.rotate({1, 0, 0}), right);
    expect_near(q.rotate({0, 0, 1}), back);
}

}  // namespace
}  // namespace steadylight
