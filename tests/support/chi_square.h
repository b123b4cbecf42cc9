// Pearson's chi-square test of a direction sampler against its pdf, binned over the sphere in
// (cos theta, phi) (Mitsuba's test03_chi2), shared by the sampling and BSDF tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include "steadylight/base/rng.h"
#include "steadylight/base/vec.h"

namespace steadylight::testing {

inline Vec3 direction(float cos_theta, float phi) {
    const float sin_theta = std::sqrt(std::max(0.0f, 1 - cos_theta * cos_theta));
    return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

/// Upper chi-square quantile for `dof` degrees of freedom by the Wilson-Hilferty cube-root
/// normal approximation (accurate to about 1% for dof > 30). z = 4.753 is the standard normal
/// quantile for a false-alarm rate of 1e-6.
inline double chi2_bound(int dof, double z = 4.753) {
    const double k = dof, c = 1 - 2 / (9 * k) + z * std::sqrt(2 / (9 * k));
    return k * c * c * c;
}

struct Chi2 {
    double statistic = 0;
    int dof = 0;
};

/// Draws `n` directions from `sample` (std::nullopt: a failed sample, which lands in no cell, as
/// the pdf's missing mass predicts) and compares them with `pdf` over n_cos x n_phi cells of
/// (cos theta in [z_min, 1], phi). Expected counts integrate the pdf over each cell; cells
/// expecting fewer than 5 samples are pooled into one.
inline Chi2 chi2_test(const std::function<std::optional<Vec3>(Pcg32&)>& sample, const std::function<float(Vec3)>& pdf,
                      float z_min, int n_cos, int n_phi, int n, uint64_t seed = 7) {
    std::vector<double> observed(size_t(n_cos * n_phi), 0.0);
    Pcg32 rng(seed);
    for (int s = 0; s < n; ++s) {
        const std::optional<Vec3> w = sample(rng);
        if (!w) continue;
        const float phi = std::atan2(w->y, w->x) + (w->y < 0 ? 2 * pi : 0);
        const int i = std::clamp(int((w->z - z_min) / (1 - z_min) * float(n_cos)), 0, n_cos - 1);
        const int j = std::clamp(int(phi / (2 * pi) * float(n_phi)), 0, n_phi - 1);
        observed[size_t(i * n_phi + j)] += 1;
    }
    constexpr int sub = 8;  // midpoint sub-cells per cell side
    const double d_cos = (1 - z_min) / (n_cos * sub), d_phi = 2 * pi / (n_phi * sub);
    Chi2 result;
    double pooled_expected = 0, pooled_observed = 0;
    for (int i = 0; i < n_cos; ++i)
        for (int j = 0; j < n_phi; ++j) {
            double integral = 0;
            for (int a = 0; a < sub; ++a)
                for (int b = 0; b < sub; ++b)
                    integral +=
                        pdf(direction(float(z_min + (i * sub + a + 0.5) * d_cos), float((j * sub + b + 0.5) * d_phi)));
            const double expected = n * integral * d_cos * d_phi, obs = observed[size_t(i * n_phi + j)];
            if (expected < 5) {
                pooled_expected += expected, pooled_observed += obs;
                continue;
            }
            result.statistic += (obs - expected) * (obs - expected) / expected;
            ++result.dof;
        }
    if (pooled_expected > 0) {
        result.statistic += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
        ++result.dof;
    } else if (pooled_observed > 0) {
        result.statistic = INFINITY;  // samples where the pdf says there can be none
    }
    --result.dof;  // the counts sum to n
    return result;
}

}  // namespace steadylight::testing
