// Piecewise-constant distributions over [0,1) and [0,1)^2, built from non-negative weights per
// cell, for sampling in proportion to a table (an environment image's luminance). The 2D one is a
// marginal distribution over the rows and a conditional one within each row (Pharr, Jakob and
// Humphreys, "Physically Based Rendering", 3rd ed., §13.6.7). A cell of weight zero is never
// sampled and has pdf zero, unless every weight is zero: then the distribution is uniform.
#pragma once

#include <vector>

#include "steadylight/base/vec.h"

namespace steadylight {

/// A piecewise-constant distribution over [0, 1) with `size()` equal cells.
class Distribution1D {
public:
    Distribution1D() = default;
    /// `weights` finite and not negative (checked), at least one.
    explicit Distribution1D(std::vector<float> weights);

    struct Sample {
        float x = 0;    // in [0, 1), inside cell `index`
        float pdf = 0;  // over [0, 1]: pdf(x)
        int index = 0;
    };
    /// The x whose cumulative distribution is u (u in [0, 1)): inside a cell of non-zero weight.
    Sample sample(float u) const;
    /// The density at x over [0, 1] (x outside [0, 1) counts as the nearest cell).
    float pdf(float x) const { return cell_pdf(cell(x)); }
    /// The density over [0, 1] in cell `index`: its weight over the mean weight.
    float cell_pdf(int index) const;
    /// The cell that holds x.
    int cell(float x) const;
    int size() const { return int(m_weights.size()); }
    /// The mean weight (the integral of the weights as a function over [0, 1]); 0 when all are.
    double mean_weight() const { return m_mean; }

private:
    std::vector<float> m_weights;  // uniform (all 1) when the given ones are all zero
    std::vector<float> m_cdf;      // size() + 1 values from 0 to exactly 1; flat across zero cells
    double m_mean = 0;             // of the given weights
    double m_inv_mean = 0;         // of m_weights; in double, as a float overflows for weights near 1e-38
};

/// A piecewise-constant distribution over [0, 1)^2 with width x height cells, from weights laid
/// out row-major: cell (column i, row j) holds weights[j * width + i] and covers
/// x in [i, i+1) / width, y in [j, j+1) / height (for an image: x to the right, y down the rows).
class Distribution2D {
public:
    Distribution2D() = default;
    /// `weights` finite and not negative (checked), width * height of them.
    Distribution2D(const std::vector<float>& weights, int width, int height);

    struct Sample {
        Vec2 uv;        // in [0, 1)^2, inside a cell of non-zero weight
        float pdf = 0;  // over [0, 1]^2: pdf(uv)
    };
    /// The point that u (in [0, 1)^2) maps to: u.y picks the row by the marginal distribution,
    /// u.x the place in it by that row's conditional one.
    Sample sample(Vec2 u) const;
    /// The density at uv over [0, 1]^2: the cell's weight over the mean weight.
    float pdf(Vec2 uv) const;
    /// The cell that holds uv (uv outside [0, 1)^2 counts as the nearest cell).
    struct Cell {
        int column = 0, row = 0;
    };
    Cell cell(Vec2 uv) const;
    int width() const { return int(m_rows.empty() ? 0 : m_rows.front().size()); }
    int height() const { return int(m_rows.size()); }
    double mean_weight() const { return m_marginal.mean_weight(); }

private:
    std::vector<Distribution1D> m_rows;  // the conditional distribution within each row
    Distribution1D m_marginal;           // over the rows, from their mean weights
};

}  // namespace steadylight
