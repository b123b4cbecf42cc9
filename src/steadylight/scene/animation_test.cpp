#include "steadylight/scene/animation.h"

#include <gtest/gtest.h>

namespace steadylight {
namespace {

Track<Vec3> track(Interpolation interpolation, std::vector<float> times, std::vector<Vec3> values) {
    return {interpolation, std::move(times), std::move(values)};
}

TEST(Animation, LinearTrackInterpolatesBetweenKeys) {
    const auto t = track(Interpolation::linear, {0, 1, 3}, {{0, 0, 0}, {2, 0, 0}, {2, 4, 0}});
    EXPECT_EQ(t.evaluate(0.5f), (Vec3{1, 0, 0}));
    EXPECT_EQ(t.evaluate(2.0f), (Vec3{2, 2, 0}));
}

TEST(Animation, TrackHoldsItsEndValuesOutsideItsKeys) {
    const auto t = track(Interpolation::linear, {1, 2}, {{1, 1, 1}, {3, 3, 3}});
    EXPECT_EQ(t.evaluate(-5), (Vec3{1, 1, 1}));
    EXPECT_EQ(t.evaluate(9), (Vec3{3, 3, 3}));
}

TEST(Animation, StepTrackHoldsEachKeyUntilTheNext) {
    const auto t = track(Interpolation::step, {0, 1}, {{0, 0, 0}, {5, 5, 5}});
    EXPECT_EQ(t.evaluate(0.99f), (Vec3{0, 0, 0}));
    EXPECT_EQ(t.evaluate(1.0f), (Vec3{5, 5, 5}));
}

TEST(Animation, ColourTrackStepsOrInterpolatesEachChannel) {
    Track<Rgb> step{Interpolation::step, {0, 1}, {Rgb{}, Rgb{17, 12, 4}}};
    EXPECT_EQ(step.evaluate(0.99f), Rgb{});
    EXPECT_EQ(step.evaluate(1.0f), (Rgb{17, 12, 4}));
    Track<Rgb> linear{Interpolation::linear, {0, 2}, {Rgb{}, Rgb{2, 4, 8}}};
    EXPECT_EQ(linear.evaluate(1.0f), (Rgb{1, 2, 4}));
    EXPECT_FALSE(linear.is_constant());
}

TEST(Animation, CubicSplineFollowsHermiteBasis) {
    // Keys 0 -> 1 with zero tangents: the Hermite curve is smoothstep, 0.5 at the middle.
    const auto t =
        track(Interpolation::cubic_spline, {0, 2}, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {0, 0, 0}});
    EXPECT_NEAR(t.evaluate(1).x, 0.5f, 1e-6f);
    EXPECT_NEAR(t.evaluate(0.5f).x, 0.15625f, 1e-6f);  // 3(1/4)^2 - 2(1/4)^3
}

TEST(Animation, RotationTrackSlerps) {
    Track<Quat> t{Interpolation::linear, {0, 1}, {Quat{}, Quat::from_axis_angle({0, 1, 0}, pi)}};
    const Vec3 v = t.evaluate(0.5f).rotate({1, 0, 0});
    EXPECT_NEAR(v.x, 0, 1e-5f);
    EXPECT_NEAR(std::abs(v.z), 1, 1e-5f);
}

TEST(Animation, ConstantTrackDoesNotMakeAnObjectAnimated) {
    AnimatedTrs trs;
    trs.translation_track = track(Interpolation::linear, {0, 1}, {{1, 2, 3}, {1, 2, 3}});
    EXPECT_FALSE(trs.is_animated());
    trs.translation_track->values[1] = {1, 2, 4};
    EXPECT_TRUE(trs.is_animated());
}

TEST(Animation, TrackReplacesTheFixedComponent) {
    AnimatedTrs trs;
    trs.translation = {100, 100, 100};
    trs.scale = {2, 2, 2};
    trs.translation_track = track(Interpolation::linear, {0, 1}, {{0, 0, 0}, {1, 0, 0}});
    EXPECT_EQ(trs.evaluate(1).point({1, 1, 1}), (Vec3{3, 2, 2}));
}

TEST(Animation, ChainAppliesParentAfterChild) {
    AnimatedTrs parent, child;
    parent.translation = {10, 0, 0};
    child.scale = {2, 2, 2};
    EXPECT_EQ(evaluate_chain({parent, child}, 0).point({1, 0, 0}), (Vec3{12, 0, 0}));
}

}  // namespace
}  // namespace steadylight
