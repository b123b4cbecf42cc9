// Piecewise-constant distributions (distribution_2d.h): samples fall in each cell in proportion
// to its weight, the pdf integrates to one and agrees with the samples, and zero cells are never
// sampled.
#include "steadylight/base/distribution_2d.h"

#include <gtest/gtest.h>

#include <vector>

#include "steadylight/base/rng.h"
#include "support/chi_square.h"

namespace steadylight {
namespace {

using testing::chi2_bound;

/// Pearson's statistic of `counts` against `n` samples spread in proportion to `weights`,
/// over the cells of non-zero weight; fails when a zero cell has a sample.
void expect_counts_follow_weights(const std::vector<int>& counts, const std::vector<float>& weights, int n) {
    double total = 0;
    for (float w : weights) total += w;
    double statistic = 0;
    int dof = -1;  // the counts sum to n
    for (size_t i = 0; i < weights.size(); ++i) {
        if (weights[i] == 0) {
            EXPECT_EQ(counts[i], 0) << "cell " << i << " has weight zero";
            continue;
        }
        const double expected = n * weights[i] / total;
        statistic += (counts[i] - expected) * (counts[i] - expected) / expected;
        ++dof;
    }
    EXPECT_LT(statistic, chi2_bound(dof)) << "dof " << dof;
}

/// Weights with zero cells, a zero row, a large spread and a tiny cell, width x height.
std::vector<float> uneven_weights(int width, int height) {
    std::vector<float> weights(size_t(width) * size_t(height));
    Pcg32 rng(11);
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i) {
            float w = rng.next_float() * (1 + 20 * float(i == 3 && j == 2));
            if ((i + j) % 5 == 0 || j == 4) w = 0;
            weights[size_t(j * width + i)] = w;
        }
    return weights;
}

TEST(Distribution1D, SamplesFollowTheWeightsAndSkipZeroCells) {
    const std::vector<float> weights = {0, 1, 3, 0, 0, 0.5f, 2, 0};
    const Distribution1D distribution(weights);
    std::vector<int> counts(weights.size());
    Pcg32 rng(1);
    const int n = 100'000;
    for (int s = 0; s < n; ++s) {
        const Distribution1D::Sample sample = distribution.sample(rng.next_float());
        ASSERT_GE(sample.x, 0.0f);
        ASSERT_LT(sample.x, 1.0f);
        ASSERT_EQ(distribution.cell(sample.x), sample.index);
        ASSERT_EQ(distribution.pdf(sample.x), sample.pdf);
        ++counts[size_t(sample.index)];
    }
    expect_counts_follow_weights(counts, weights, n);
}

TEST(Distribution1D, PdfIsTheWeightOverTheMeanAndIntegratesToOne) {
    const Distribution1D distribution({1, 0, 3});
    EXPECT_FLOAT_EQ(distribution.pdf(0.1f), 0.75f);
    EXPECT_EQ(distribution.pdf(0.5f), 0.0f);
    EXPECT_FLOAT_EQ(distribution.pdf(0.9f), 2.25f);
    EXPECT_FLOAT_EQ(float(distribution.mean_weight()), 4.0f / 3);
    double integral = 0;
    for (int i = 0; i < 3; ++i) integral += distribution.cell_pdf(i) / 3.0;
    EXPECT_NEAR(integral, 1.0, 1e-6);
}

// Sampling is the inverse of the cumulative distribution: u at a cell's start gives the start of
// the cell, and u just below 1 stays below 1 inside the last non-zero cell.
TEST(Distribution1D, SampleInvertsTheCumulativeDistribution) {
    const Distribution1D distribution({1, 1, 2, 0});
    EXPECT_FLOAT_EQ(distribution.sample(0.25f).x, 0.25f);
    EXPECT_FLOAT_EQ(distribution.sample(0.5f).x, 0.5f);
    EXPECT_FLOAT_EQ(distribution.sample(0.75f).x, 0.625f);
    const Distribution1D::Sample last = distribution.sample(0x1.fffffep-1f);
    EXPECT_EQ(last.index, 2);
    EXPECT_LT(last.x, 0.75f);
}

// Weights near the smallest floats (their mean's inverse is beyond the largest) or the largest.
TEST(Distribution1D, PdfDoesNotDependOnTheWeightsScale) {
    for (const float scale : {1e-44f, 1e-30f, 1.0f, 1e37f}) {
        const Distribution1D distribution({scale, 3 * scale});
        EXPECT_FLOAT_EQ(distribution.pdf(0.1f), 0.5f) << scale;
        EXPECT_FLOAT_EQ(distribution.pdf(0.9f), 1.5f) << scale;
        EXPECT_FLOAT_EQ(distribution.sample(0.625f).x, 0.75f) << scale;
    }
}

TEST(Distribution1D, AllZeroWeightsGiveTheUniformDistribution) {
    const Distribution1D distribution(std::vector<float>(4, 0.0f));
    EXPECT_EQ(distribution.mean_weight(), 0.0);
    for (float x : {0.0f, 0.3f, 0.99f}) EXPECT_EQ(distribution.pdf(x), 1.0f);
    EXPECT_FLOAT_EQ(distribution.sample(0.6f).x, 0.6f);
}

TEST(Distribution2D, SamplesFollowTheWeightsAndSkipZeroCellsAndRows) {
    const int width = 7, height = 6, n = 200'000;
    const std::vector<float> weights = uneven_weights(width, height);
    const Distribution2D distribution(weights, width, height);
    std::vector<int> counts(weights.size());
    Pcg32 rng(2);
    for (int s = 0; s < n; ++s) {
        const Distribution2D::Sample sample = distribution.sample(rng.next_vec2());
        ASSERT_TRUE(sample.uv.x >= 0 && sample.uv.x < 1 && sample.uv.y >= 0 && sample.uv.y < 1);
        ASSERT_EQ(distribution.pdf(sample.uv), sample.pdf);
        ASSERT_GT(sample.pdf, 0.0f);
        ++counts[size_t(int(sample.uv.y * height) * width + int(sample.uv.x * width))];
    }
    expect_counts_follow_weights(counts, weights, n);
}

TEST(Distribution2D, PdfIsTheCellsShareOfTheWeightAndIntegratesToOne) {
    const int width = 7, height = 6;
    const std::vector<float> weights = uneven_weights(width, height);
    const Distribution2D distribution(weights, width, height);
    double total = 0;
    for (float w : weights) total += w;
    double integral = 0;
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i) {
            const float pdf = distribution.pdf({(i + 0.5f) / width, (j + 0.5f) / height});
            EXPECT_NEAR(pdf, weights[size_t(j * width + i)] / total * width * height, 1e-5 * pdf);
            integral += pdf / (width * height);
        }
    EXPECT_NEAR(integral, 1.0, 1e-5);
    EXPECT_NEAR(distribution.mean_weight(), total / (width * height), 1e-6 * total);
}

TEST(Distribution2D, AllZeroWeightsGiveTheUniformDistribution) {
    const Distribution2D distribution(std::vector<float>(12, 0.0f), 4, 3);
    const Distribution2D::Sample sample = distribution.sample({0.3f, 0.8f});
    EXPECT_FLOAT_EQ(sample.uv.x, 0.3f);
    EXPECT_FLOAT_EQ(sample.uv.y, 0.8f);
    EXPECT_EQ(sample.pdf, 1.0f);
    EXPECT_EQ(distribution.pdf({0.9f, 0.1f}), 1.0f);
}

// One cell among a million cells with a weight far below the others' still gets its share: the
// cumulative sums are formed in double precision.
TEST(Distribution2D, ALoneCellInALargeTableIsSampledAndOthersAreNot) {
    const int width = 2048, height = 1024;
    std::vector<float> weights(size_t(width) * height, 0.0f);
    weights[size_t(700 * width + 1500)] = 1e-30f;
    const Distribution2D distribution(weights, width, height);
    Pcg32 rng(3);
    for (int s = 0; s < 1000; ++s) {
        const Vec2 uv = distribution.sample(rng.next_vec2()).uv;
        ASSERT_EQ(int(uv.x * width), 1500);
        ASSERT_EQ(int(uv.y * height), 700);
    }
    EXPECT_FLOAT_EQ(distribution.pdf({(1500 + 0.5f) / width, (700 + 0.5f) / height}), float(width) * height);
}

}  // namespace
}  // namespace steadylight
