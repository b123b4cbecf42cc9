#include "steadylight/photons/point_index.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <limits>
#include <optional>

#include "steadylight/base/check.h"

namespace steadylight {
namespace {

// Ranges this small are leaves, scanned point by point.
constexpr uint32_t leaf_size = 16;
// updated() builds a range this small again, as a tree of its own, where a quarter or more of
// its points changed: an object that was not there before brings its points all into the one
// leaf whose empty cell it fills (about a thousand on BALL's ball), and where it takes points
// away, the leaves left thin make searches visit more of them.
constexpr uint32_t rebuilt_size = 1024;
// m_axis's mark of a range built again.
constexpr uint8_t rebuilt_range = 3;
// Ranges this large build their two halves in parallel (the result does not depend on it).
constexpr uint32_t parallel_build_size = 32 * 1024;

/// The k best neighbours so far; once k are found, a max-heap with the farthest on top, and the
/// search radius shrinks to the farthest one's.
class BoundedHeap {
public:
    BoundedHeap(Neighbour* items, int k, float max_distance2) : m_items(items), m_k(k), m_radius2(max_distance2) {}

    float radius2() const { return m_radius2; }
    int size() const { return m_count; }

    void offer(uint32_t index, float distance2) {
        if (distance2 > m_radius2) return;
        const Neighbour candidate{index, distance2};
        if (m_count < m_k) {
            // Filling up: no order needed until the k-th arrives.
            m_items[m_count++] = candidate;
            if (m_count == m_k) {
                std::make_heap(m_items, m_items + m_k, nearer_neighbour);
                m_radius2 = m_items[0].distance2;
            }
        } else if (nearer_neighbour(candidate, m_items[0])) {
            replace_top(candidate);
            m_radius2 = m_items[0].distance2;
        }
    }

    /// Sorts the items nearest first.
    void sort() { std::sort(m_items, m_items + m_count, nearer_neighbour); }

private:
    /// Puts `item` in place of the farthest and sifts it down.
    void replace_top(const Neighbour& item) {
        int i = 0;
        for (;;) {
            int child = 2 * i + 1;
            if (child >= m_k) break;
            if (child + 1 < m_k && nearer_neighbour(m_items[child], m_items[child + 1])) ++child;
            if (!nearer_neighbour(item, m_items[child])) break;
            m_items[i] = m_items[child];
            i = child;
        }
        m_items[i] = item;
    }

    Neighbour* m_items;
    int m_k;
    int m_count = 0;
    float m_radius2;
};

/// The nearest neighbour so far (k = 1, the irradiance-photon look-up of every gather ray):
/// the heap's job without a heap.
class NearestOne {
public:
    explicit NearestOne(float max_distance2) : m_radius2(max_distance2) {}

    float radius2() const { return m_radius2; }
    int size() const { return m_found ? 1 : 0; }
    const Neighbour& best() const { return m_best; }

    void offer(uint32_t index, float distance2) {
        if (distance2 > m_radius2) return;
        const Neighbour candidate{index, distance2};
        if (!m_found || nearer_neighbour(candidate, m_best)) m_best = candidate, m_radius2 = distance2, m_found = true;
    }

private:
    Neighbour m_best{0, 0};
    float m_radius2;
    bool m_found = false;
};

/// Every point within a fixed radius (PointIndex::within), in the order they are offered.
class EveryWithin {
public:
    EveryWithin(std::vector<Neighbour>& out, float max_distance2) : m_out(out), m_radius2(max_distance2) {}

    float radius2() const { return m_radius2; }
    void offer(uint32_t index, float distance2) {
        if (distance2 <= m_radius2) m_out.push_back({index, distance2});
    }

private:
    std::vector<Neighbour>& m_out;
    float m_radius2;
};

/// The ids of an index searched on its own: its points' own (`removed` for those an update took out).
struct OwnIds {
    static bool keeps(uint32_t id) { return id != PointIndex::removed; }
    uint32_t operator()(uint32_t, uint32_t id) const { return id; }
};

/// The ids of a PointIndex::Mapped, by the point's place in the tree.
struct MappedIds {
    const uint32_t* ids;
    static bool keeps(uint32_t id) { return id != PointIndex::removed; }
    uint32_t operator()(uint32_t position, uint32_t) const { return ids[position]; }
};

int widest_axis(Vec3 lower, Vec3 upper) {
    const Vec3 extent = upper - lower;
    return extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
}

}  // namespace

PointIndex::PointIndex(const std::vector<Vec3>& points) {
    SL_CHECK(points.size() < std::numeric_limits<uint32_t>::max());
    if (points.empty()) return;
    m_entries.resize(points.size());
    Vec3 lower = points[0], upper = points[0];
    for (uint32_t i = 0; i < points.size(); ++i) {
        m_entries[i] = {{points[i].x, points[i].y, points[i].z}, i};
        lower = min(lower, points[i]), upper = max(upper, points[i]);
    }
    m_axis.assign(points.size(), 0);
    m_split.assign(points.size(), 0.0f);
    build(0, uint32_t(points.size()), lower, upper);
}

PointIndex PointIndex::answering_as(const std::vector<Vec3>& points, const std::vector<uint32_t>& ids) {
    PointIndex index(points);  // split ties broken by position in `points`, as for any index
    for (Entry& e : index.m_entries) e.id = ids[e.id];
    return index;
}

void PointIndex::build(uint32_t begin, uint32_t end, Vec3 lower, Vec3 upper) {
    if (end - begin <= leaf_size) return;
    // Split the range's box across its widest side at the median point.
    const int axis = widest_axis(lower, upper);
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(m_entries.begin() + begin, m_entries.begin() + mid, m_entries.begin() + end,
                     [axis](const Entry& a, const Entry& b) {
                         return a.p[axis] != b.p[axis] ? a.p[axis] < b.p[axis] : a.id < b.id;
                     });
    m_axis[mid] = uint8_t(axis);
    m_split[mid] = m_entries[mid].p[axis];
    Vec3 left_upper = upper, right_lower = lower;
    left_upper[axis] = right_lower[axis] = m_split[mid];
    const auto left = [&] { build(begin, mid, lower, left_upper); };
    const auto right = [&] { build(mid, end, right_lower, upper); };
    if (end - begin >= parallel_build_size) {
        tbb::parallel_invoke(left, right);
    } else {
        left();
        right();
    }
}

uint32_t PointIndex::leaf_of(Vec3 p) const {
    uint32_t begin = 0, end = uint32_t(m_entries.size());
    while (end - begin > leaf_size) {  // as search() descends
        const uint32_t mid = begin + (end - begin) / 2;
        const int axis = m_axis[mid];
        if (p[axis] - m_split[mid] < 0)
            end = mid;
        else
            begin = mid;
    }
    return begin;
}

PointIndex PointIndex::updated(const std::vector<uint32_t>& ids_by_id, const std::vector<Vec3>& added,
                               const std::vector<uint32_t>& added_ids) const {
    SL_CHECK(ids_by_id.size() == m_entries.size() && added.size() == added_ids.size() && m_added_first.empty());
    if (m_entries.empty()) return answering_as(added, added_ids);
    PointIndex out;
    out.m_entries = m_entries;
    for (Entry& e : out.m_entries) e.id = ids_by_id[e.id];
    out.m_axis = m_axis;
    out.m_split = m_split;
    // The added points, sorted by their leaf's first position (a counting sort).
    std::vector<uint32_t> leaf(added.size());
    out.m_added_first.assign(m_entries.size() + 1, 0);
    for (size_t i = 0; i < added.size(); ++i) ++out.m_added_first[(leaf[i] = leaf_of(added[i])) + 1];
    for (size_t i = 1; i < out.m_added_first.size(); ++i) out.m_added_first[i] += out.m_added_first[i - 1];
    std::vector<uint32_t> next(out.m_added_first.begin(), out.m_added_first.end() - 1);
    out.m_added.resize(added.size());
    for (size_t i = 0; i < added.size(); ++i)
        out.m_added[next[leaf[i]]++] = {{added[i].x, added[i].y, added[i].z}, added_ids[i]};
    // The ranges much changed, built again (those of their added points stay in m_added, where
    // no search reaches them).
    std::vector<uint32_t> removed_before(m_entries.size() + 1, 0);
    for (size_t i = 0; i < m_entries.size(); ++i)
        removed_before[i + 1] = removed_before[i] + (out.m_entries[i].id == removed ? 1 : 0);
    out.rebuild_changed(0, uint32_t(m_entries.size()), removed_before);
    return out;
}

void PointIndex::rebuild_changed(uint32_t begin, uint32_t end, const std::vector<uint32_t>& removed_before) {
    const uint32_t size = end - begin;
    if (size <= leaf_size) return;
    const uint32_t mid = begin + size / 2;
    const uint32_t changed = removed_before[end] - removed_before[begin] + m_added_first[end] - m_added_first[begin];
    if (size > rebuilt_size || 4 * changed < size) {
        rebuild_changed(begin, mid, removed_before);
        rebuild_changed(mid, end, removed_before);
        return;
    }
    std::vector<Vec3> points;
    std::vector<uint32_t> ids;
    const auto take = [&](const Entry& e) {
        if (e.id == removed) return;
        points.push_back({e.p[0], e.p[1], e.p[2]});
        ids.push_back(e.id);
    };
    std::for_each(m_entries.begin() + begin, m_entries.begin() + end, take);
    std::for_each(m_added.begin() + m_added_first[begin], m_added.begin() + m_added_first[end], take);
    m_axis[mid] = rebuilt_range;
    m_rebuilt_mids.push_back(mid);  // ranges are met left to right: ascending
    m_rebuilt.push_back(answering_as(points, ids));
}

template <class Heap, class Ids>
void PointIndex::search(uint32_t begin, uint32_t end, const float p[3], CellDistance cell, Heap& heap, Ids ids) const {
    const auto offer = [&](const Entry& e, uint32_t id) {
        if (Ids::keeps(id)) heap.offer(id, distance2({e.p[0], e.p[1], e.p[2]}, {p[0], p[1], p[2]}));
    };
    // Descend towards p; visit the far half of a split afterwards if the heap's radius still
    // reaches the far half's cell. The distance to a cell is kept per axis and updated as the
    // search crosses splitting planes (Arya & Mount 1993), which prunes far better than the
    // distance to the last plane alone.
    while (end - begin > leaf_size) {
        const uint32_t mid = begin + (end - begin) / 2;
        const int axis = m_axis[mid];
        if (axis == rebuilt_range) {
            const PointIndex& tree = m_rebuilt[size_t(
                std::lower_bound(m_rebuilt_mids.begin(), m_rebuilt_mids.end(), mid) - m_rebuilt_mids.begin())];
            // Its points lie in this range's cell: searched from the cell's distance on.
            if (!tree.m_entries.empty()) tree.search(0, uint32_t(tree.m_entries.size()), p, cell, heap, OwnIds{});
            return;
        }
        const float d = p[axis] - m_split[mid];
        if (d < 0) {
            search(begin, mid, p, cell, heap, ids);
            begin = mid;
        } else {
            search(mid, end, p, cell, heap, ids);
            end = mid;
        }
        const float offset = cell.offset[axis];
        cell.distance2 += d * d - offset * offset;
        cell.offset[axis] = d;
        if (cell.distance2 > heap.radius2()) return;
    }
    for (uint32_t i = begin; i < end; ++i) offer(m_entries[i], ids(i, m_entries[i].id));
    if (m_added_first.empty()) return;
    for (uint32_t i = m_added_first[begin]; i < m_added_first[end]; ++i) offer(m_added[i], m_added[i].id);
}

std::vector<uint32_t> PointIndex::in_tree_order(const std::vector<uint32_t>& by_id) const {
    SL_CHECK(by_id.size() == m_entries.size() && m_added_first.empty());  // an updated index is not Mapped
    std::vector<uint32_t> ids(m_entries.size());
    for (size_t i = 0; i < m_entries.size(); ++i) ids[i] = by_id[m_entries[i].id];
    return ids;
}

template <class Heap, class Part>
void PointIndex::search_part(const float p[3], Heap& heap, const Part& part) {
    const auto& [index, ids] = part;
    if (!index->m_entries.empty()) index->search(0, uint32_t(index->m_entries.size()), p, CellDistance{}, heap, ids);
}

template <class... Parts>
std::optional<Neighbour> PointIndex::search_nearest(Vec3 p, float max_distance2, std::optional<Neighbour> known,
                                                    Parts... parts) {
    const float query[3] = {p.x, p.y, p.z};
    NearestOne nearest(max_distance2);
    if (known) nearest.offer(known->index, known->distance2);
    (search_part(query, nearest, parts), ...);
    if (!nearest.size()) return std::nullopt;
    return nearest.best();
}

template <class... Parts>
void PointIndex::search_all(Vec3 p, int k, float max_distance2, Order order, std::vector<Neighbour>& out,
                            Parts... parts) {
    out.clear();
    if (k <= 0) return;
    if (k == 1) {
        if (const std::optional<Neighbour> found = search_nearest(p, max_distance2, std::nullopt, parts...))
            out.push_back(*found);
        return;
    }
    const float query[3] = {p.x, p.y, p.z};
    out.resize(size_t(k));
    BoundedHeap heap(out.data(), k, max_distance2);
    (search_part(query, heap, parts), ...);
    if (order == Order::nearest_first) heap.sort();  // else the heap's order: the farthest on top
    out.resize(size_t(heap.size()));
}

template <class... Parts>
void PointIndex::search_within(Vec3 p, float max_distance2, std::vector<Neighbour>& out, Parts... parts) {
    out.clear();
    const float query[3] = {p.x, p.y, p.z};
    EveryWithin collector(out, max_distance2);
    (search_part(query, collector, parts), ...);
}

void PointIndex::within(Vec3 p, float max_distance2, std::vector<Neighbour>& out) const {
    search_within(p, max_distance2, out, std::pair{this, OwnIds{}});
}

void PointIndex::within(Mapped a, Mapped b, Vec3 p, float max_distance2, std::vector<Neighbour>& out) {
    search_within(p, max_distance2, out, std::pair{a.index, MappedIds{a.ids}}, std::pair{b.index, MappedIds{b.ids}});
}

std::optional<Neighbour> PointIndex::nearest(Vec3 p, float max_distance2, std::optional<Neighbour> known) const {
    return search_nearest(p, max_distance2, known, std::pair{this, OwnIds{}});
}

void PointIndex::k_nearest(Vec3 p, int k, float max_distance2, std::vector<Neighbour>& out, Order order) const {
    search_all(p, k, max_distance2, order, out, std::pair{this, OwnIds{}});
}

void PointIndex::k_nearest(Mapped a, Vec3 p, int k, float max_distance2, std::vector<Neighbour>& out, Order order) {
    search_all(p, k, max_distance2, order, out, std::pair{a.index, MappedIds{a.ids}});
}

void PointIndex::k_nearest(Mapped a, Mapped b, Vec3 p, int k, float max_distance2, std::vector<Neighbour>& out,
                           Order order) {
    search_all(p, k, max_distance2, order, out, std::pair{a.index, MappedIds{a.ids}},
               std::pair{b.index, MappedIds{b.ids}});
}

}  // namespace steadylight
