// Every step-th pixel centre of an image, row by row: where the influence is estimated
// (InfluenceMap) and what a still view keeps of its pixel centres for it (KeptCentreRays).
#pragma once

#include <cstddef>

namespace steadylight {

struct SampleGrid {
    int width = 0, height = 0, step = 1;

    int columns() const { return (width + step - 1) / step; }
    int rows() const { return (height + step - 1) / step; }
    size_t size() const { return size_t(columns()) * size_t(rows()); }
    /// Sample i's pixel.
    int x(size_t i) const { return int(i % size_t(columns())) * step; }
    int y(size_t i) const { return int(i / size_t(columns())) * step; }
    /// The sample whose step-by-step block holds pixel (x, y).
    size_t at(int x, int y) const { return size_t(y / step) * size_t(columns()) + size_t(x / step); }
};

}  // namespace steadylight
