#include "steadylight/photons/point_index.h"

#include <nanoflann.hpp>

#include <algorithm>

namespace steadylight {

/// nanoflann's dataset adaptor over the point vector.
struct PointCloud {
    const std::vector<Vec3>* points;
    size_t kdtree_get_point_count() const { return points->size(); }
    float kdtree_get_pt(size_t i, size_t dim) const { return (*points)[i][int(dim)]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const { return false; }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PointCloud>, PointCloud, 3, uint32_t>;

struct PointIndex::Tree {
    std::vector<Vec3> points;
    PointCloud cloud{&points};
    KdTree tree;
    explicit Tree(std::vector<Vec3> p)
        : points(std::move(p)), tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {}
};

PointIndex::PointIndex() = default;
PointIndex::~PointIndex() = default;
PointIndex::PointIndex(PointIndex&&) noexcept = default;
PointIndex& PointIndex::operator=(PointIndex&&) noexcept = default;

PointIndex::PointIndex(std::vector<Vec3> points) {
    if (!points.empty()) m_tree = std::make_unique<Tree>(std::move(points));
}

size_t PointIndex::size() const { return m_tree ? m_tree->points.size() : 0; }

void PointIndex::k_nearest(Vec3 p, int k, float max_distance2, std::vector<Neighbour>& out) const {
    out.clear();
    if (!m_tree || k <= 0) return;
    thread_local std::vector<uint32_t> indices;
    thread_local std::vector<float> distances2;
    indices.resize(static_cast<size_t>(k));
    distances2.resize(static_cast<size_t>(k));
    const float query[3] = {p.x, p.y, p.z};
    const size_t found = m_tree->tree.knnSearch(query, size_t(k), indices.data(), distances2.data());
    for (size_t i = 0; i < found; ++i)
        if (distances2[i] <= max_distance2) out.push_back({indices[i], distances2[i]});
    std::sort(out.begin(), out.end(), [](const Neighbour& a, const Neighbour& b) {
        return a.distance2 != b.distance2 ? a.distance2 < b.distance2 : a.index < b.index;
    });
}

}  // namespace steadylight
