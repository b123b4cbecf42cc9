// A kd-tree over points for k-nearest-neighbour queries, wrapping nanoflann (DESIGN.md §4).
// Photon maps and the irradiance photons use it; results are sorted by distance, ties broken by
// index, so queries are deterministic.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "steadylight/base/vec.h"

namespace steadylight {

struct Neighbour {
    uint32_t index;
    float distance2;
};

class PointIndex {
public:
    PointIndex();
    explicit PointIndex(std::vector<Vec3> points);
    ~PointIndex();
    PointIndex(PointIndex&&) noexcept;
    PointIndex& operator=(PointIndex&&) noexcept;

    size_t size() const;

    /// The up to `k` nearest points within sqrt(max_distance2) of `p`, nearest first.
    void k_nearest(Vec3 p, int k, float max_distance2, std::vector<Neighbour>& out) const;

private:
    struct Tree;  // owns the points; on the heap so that nanoflann's pointer to them stays valid
    std::unique_ptr<Tree> m_tree;
};

}  // namespace steadylight
