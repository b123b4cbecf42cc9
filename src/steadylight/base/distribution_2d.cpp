#include "steadylight/base/distribution_2d.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "steadylight/base/check.h"

namespace steadylight {
namespace {

constexpr float one_minus_epsilon = 0x1.fffffep-1f;  // the largest float below 1

}  // namespace

Distribution1D::Distribution1D(std::vector<float> weights) : m_weights(std::move(weights)) {
    SL_CHECK(!m_weights.empty());
    double total = 0;
    for (float w : m_weights) {
        SL_CHECK(std::isfinite(w) && w >= 0);
        total += w;
    }
    const int n = size();
    m_mean = total / n;
    if (total == 0) {
        std::fill(m_weights.begin(), m_weights.end(), 1.0f);
        total = n;
    }
    m_inv_mean = n / total;
    // The cumulative distribution, flat across a zero cell (copied, not recomputed, so that
    // rounding cannot give it a sliver of width) and exactly 1 from the last non-zero cell on.
    m_cdf.assign(size_t(n) + 1, 0.0f);
    double running = 0;
    int last = 0;
    for (int i = 0; i < n; ++i) {
        running += m_weights[size_t(i)];
        m_cdf[size_t(i) + 1] = m_weights[size_t(i)] == 0 ? m_cdf[size_t(i)] : float(running / total);
        if (m_weights[size_t(i)] > 0) last = i;
    }
    std::fill(m_cdf.begin() + last + 1, m_cdf.end(), 1.0f);
}

int Distribution1D::cell(float x) const {
    if (!(x > 0)) return 0;  // NaN too
    return x >= 1 ? size() - 1 : std::min(int(x * float(size())), size() - 1);
}

float Distribution1D::cell_pdf(int index) const { return float(m_weights[size_t(index)] * m_inv_mean); }

Distribution1D::Sample Distribution1D::sample(float u) const {
    u = std::clamp(u, 0.0f, one_minus_epsilon);
    // The last cell whose cumulative value is at most u: never a zero cell, since one of those
    // has the same value as the cell after it (and the value after the last cell, 1, exceeds u).
    const int n = size();
    const int i = std::min(int(std::upper_bound(m_cdf.begin(), m_cdf.end(), u) - m_cdf.begin()) - 1, n - 1);
    const float width = m_cdf[size_t(i) + 1] - m_cdf[size_t(i)];
    const float offset = width > 0 ? (u - m_cdf[size_t(i)]) / width : 0.5f;
    float x = std::min((float(i) + offset) / float(n), one_minus_epsilon);
    // Rounding may carry x over a cell's edge: step it back, so that pdf(x) is the cell's pdf.
    while (cell(x) > i) x = std::nextafter(x, 0.0f);
    while (cell(x) < i) x = std::nextafter(x, 1.0f);
    return {x, cell_pdf(i), i};
}

Distribution2D::Distribution2D(const std::vector<float>& weights, int width, int height) {
    SL_CHECK(width > 0 && height > 0 && weights.size() == size_t(width) * size_t(height));
    m_rows.reserve(size_t(height));
    std::vector<float> row_means(static_cast<size_t>(height));
    for (int j = 0; j < height; ++j) {
        const auto row = weights.begin() + ptrdiff_t(j) * width;
        m_rows.emplace_back(std::vector<float>(row, row + width));
        row_means[size_t(j)] = float(m_rows.back().mean_weight());
    }
    m_marginal = Distribution1D(std::move(row_means));
}

Distribution2D::Sample Distribution2D::sample(Vec2 u) const {
    const Distribution1D::Sample row = m_marginal.sample(u.y);
    const Distribution1D::Sample column = m_rows[size_t(row.index)].sample(u.x);
    return {{column.x, row.x}, row.pdf * column.pdf};
}

Distribution2D::Cell Distribution2D::cell(Vec2 uv) const {
    const int row = m_marginal.cell(uv.y);
    return {m_rows[size_t(row)].cell(uv.x), row};
}

float Distribution2D::pdf(Vec2 uv) const {
    const Cell at = cell(uv);
    return m_marginal.cell_pdf(at.row) * m_rows[size_t(at.row)].cell_pdf(at.column);
}

}  // namespace steadylight
