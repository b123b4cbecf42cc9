#include "steadylight/base/sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "steadylight/base/rng.h"
#include "support/chi_square.h"

namespace steadylight {
namespace {

using testing::Chi2;
using testing::chi2_bound;
using testing::chi2_test;
using testing::direction;

/// Midpoint rule over the sphere in (cos theta, phi), where d(omega) = d(cos theta) d(phi).
double integrate_over_sphere(const std::function<float(Vec3)>& f, int n_cos, int n_phi) {
    const double d_cos = 2.0 / n_cos, d_phi = 2 * pi / n_phi;
    double sum = 0;
    for (int i = 0; i < n_cos; ++i)
        for (int j = 0; j < n_phi; ++j) sum += f(direction(float(-1 + (i + 0.5) * d_cos), float((j + 0.5) * d_phi)));
    return sum * d_cos * d_phi;
}

void expect_follows_pdf(const std::function<Vec3(Vec2)>& sample, const std::function<float(Vec3)>& pdf, float z_min) {
    const Chi2 chi2 = chi2_test([&](Pcg32& rng) -> std::optional<Vec3> { return sample(rng.next_vec2()); }, pdf, z_min,
                                8, 16, 200'000);
    ASSERT_GT(chi2.dof, 100);
    EXPECT_LT(chi2.statistic, chi2_bound(chi2.dof)) << "dof " << chi2.dof;
}

TEST(Sampling, CosineHemisphereSamplesAreUnitVectorsAboveTheHorizon) {
    Pcg32 rng(1);
    for (int i = 0; i < 1000; ++i) {
        const Vec3 w = sample_cosine_hemisphere(rng.next_vec2());
        EXPECT_NEAR(length(w), 1.0f, 1e-5f);
        EXPECT_GE(w.z, 0.0f);
    }
}

TEST(Sampling, CosineHemispherePdfIntegratesToOne) {
    const double integral = integrate_over_sphere([](Vec3 w) { return cosine_hemisphere_pdf(w.z); }, 512, 64);
    EXPECT_NEAR(integral, 1.0, 1e-3);
}

TEST(Sampling, UniformSpherePdfIntegratesToOne) {
    EXPECT_NEAR(integrate_over_sphere([](Vec3) { return uniform_sphere_pdf(); }, 512, 64), 1.0, 1e-3);
}

TEST(Sampling, CosineHemisphereSamplesFollowTheirPdf) {
    expect_follows_pdf(
        sample_cosine_hemisphere, [](Vec3 w) { return cosine_hemisphere_pdf(w.z); }, 0.0f);
}

TEST(Sampling, UniformSphereSamplesFollowTheirPdf) {
    expect_follows_pdf(
        sample_uniform_sphere, [](Vec3) { return uniform_sphere_pdf(); }, -1.0f);
}

TEST(Sampling, UniformConePdfIntegratesToOneOverTheCone) {
    const float cos_max = 0.6f;
    const auto pdf = [&](Vec3 w) { return w.z >= cos_max ? uniform_cone_pdf(cos_max) : 0.0f; };
    EXPECT_NEAR(integrate_over_sphere(pdf, 2000, 64), 1.0, 2e-3);
}

TEST(Sampling, UniformConeSamplesFollowTheirPdf) {
    const float cos_max = 0.3f;
    expect_follows_pdf([&](Vec2 u) { return sample_uniform_cone(u, cos_max); },
                       [&](Vec3 w) { return w.z >= cos_max ? uniform_cone_pdf(cos_max) : 0.0f; }, cos_max);
}

TEST(Sampling, UniformTriangleBarycentricsLieInsideTheTriangle) {
    Pcg32 rng(2);
    for (int i = 0; i < 10'000; ++i) {
        const Vec2 b = sample_uniform_triangle(rng.next_vec2());
        EXPECT_GE(b.x, 0.0f);
        EXPECT_GE(b.y, 0.0f);
        EXPECT_LE(b.x + b.y, 1.0f + 1e-6f);
    }
}

// A uniform density has its mean at the centroid, and the corner triangle cut off at
// half the height of a vertex holds a quarter of the area, hence a quarter of the samples.
TEST(Sampling, UniformTriangleBarycentricsAreUniform) {
    constexpr int n = 200'000;
    Pcg32 rng(3);
    double sum[3] = {0, 0, 0};
    int near_vertex0 = 0;
    for (int i = 0; i < n; ++i) {
        const Vec2 b = sample_uniform_triangle(rng.next_vec2());
        const double b0 = 1.0 - b.x - b.y;
        sum[0] += b0, sum[1] += b.x, sum[2] += b.y;
        near_vertex0 += b0 > 0.5;
    }
    // Each barycentric has variance 1/18 under a uniform density: 5 standard errors is 0.0026.
    for (const double s : sum) EXPECT_NEAR(s / n, 1.0 / 3.0, 0.0027);
    EXPECT_NEAR(double(near_vertex0) / n, 0.25, 0.005);
}

TEST(Sampling, PowerHeuristicWeightsOfTwoStrategiesSumToOne) {
    const float pdfs[] = {1e-4f, 0.1f, 0.5f, 1.0f, 3.0f, 250.0f};
    for (const float a : pdfs)
        for (const float b : pdfs) EXPECT_NEAR(power_heuristic(a, b) + power_heuristic(b, a), 1.0f, 1e-6f);
}

TEST(Sampling, PowerHeuristicGivesAllWeightToTheOnlyStrategyThatCanSample) {
    EXPECT_EQ(power_heuristic(0.7f, 0.0f), 1.0f);
    EXPECT_EQ(power_heuristic(0.0f, 0.7f), 0.0f);
    EXPECT_EQ(power_heuristic(0.0f, 0.0f), 0.0f);
}

}  // namespace
}  // namespace steadylight
