// A kd-tree over points for k-nearest-neighbour queries within a radius (docs/design.md). Photon
// maps and the irradiance photons use it; results are sorted by distance, ties broken by index
// (or, for sums that need no sort, in the search's own order), so queries are deterministic.
//
// It is our own rather than nanoflann's: a balanced tree in an implicit layout (every range
// splits at its median, no pointers) searched with a bounded max-heap that starts at the
// query radius, pruning by the exact distance to each cell. nanoflann's kNN ignores the radius
// and inserts every candidate in O(k): for the k = 50 and 300 estimates of photon mapping this
// tree answers 1.3x and 2x faster, and about as fast for k <= 8 (bench/point_index_bench, README
// "Benchmarks").
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "steadylight/base/vec.h"

namespace steadylight {

struct Neighbour {
    uint32_t index;
    float distance2;
};

/// The order of every search's answer: nearer first; equal distances by index, so every result
/// is unique. (A function object, so that the heap and sort algorithms inline it.)
constexpr struct {
    bool operator()(const Neighbour& a, const Neighbour& b) const {
        return a.distance2 != b.distance2 ? a.distance2 < b.distance2 : a.index < b.index;
    }
} nearer_neighbour;

class PointIndex {
public:
    /// An id that a MappedIndex gives the points it leaves out.
    static constexpr uint32_t removed = ~0u;

    /// An index whose points answer with other ids, or not at all (`removed`): an index built
    /// once and searched as part of a set that has since lost some points and been renumbered.
    /// `ids` are in the tree's order (in_tree_order()), so a search reads them where it reads
    /// the points.
    struct Mapped {
        const PointIndex* index;
        const uint32_t* ids;
    };

    PointIndex() = default;
    explicit PointIndex(const std::vector<Vec3>& points);

    /// The points held: the tree's (those `removed` by updated() too) and those added.
    size_t size() const { return m_entries.size() + m_added.size(); }
    /// `by_id[i]` for each point i, in the order the tree keeps the points (Mapped's ids).
    std::vector<uint32_t> in_tree_order(const std::vector<uint32_t>& by_id) const;

    /// This index after its set of points has changed a little: point i answers as
    /// `ids_by_id[i]` (or not at all: `removed`), and the `added` points join it answering as
    /// `added_ids`, each filed with the leaf whose cell holds it; a small range where a quarter
    /// or more of the points changed is built again as a tree of its own. Its searches give the
    /// answers of an index built over the new set with those ids (both order by distance, then
    /// id), and making it costs a pass over the points, a descent per added one and the ranges
    /// built again, instead of a whole build: for a set that changes by a few percent at a
    /// time. It is searched on its own (not as a Mapped part), and it is not updated again.
    PointIndex updated(const std::vector<uint32_t>& ids_by_id, const std::vector<Vec3>& added,
                       const std::vector<uint32_t>& added_ids) const;

    /// How a search's answer is ordered: nearest first (ties: smaller index first); or, for a
    /// sum over the points that needs a fixed order but not a sorted one, the farthest first
    /// when all k were found and the rest in an order that depends on the index and the query
    /// alone (the search's; with fewer than k, that order throughout).
    enum class Order { nearest_first, farthest_first };

    /// The up to `k` nearest points within sqrt(max_distance2) of `p`.
    void k_nearest(Vec3 p, int k, float max_distance2, std::vector<Neighbour>& out,
                   Order order = Order::nearest_first) const;

    /// k_nearest(p, 1, max_distance2), told of a point of the index within that distance already
    /// (`known`: its id and squared distance to p): the search prunes by it from the start, as a
    /// run of nearby queries can tell each the one before's answer. The same answer either way.
    std::optional<Neighbour> nearest(Vec3 p, float max_distance2, std::optional<Neighbour> known = {}) const;

    /// k_nearest over the union of two mapped indexes (their ids distinct): the same answer as
    /// one index built over the union with those ids, since both order by distance, then id.
    static void k_nearest(Mapped a, Mapped b, Vec3 p, int k, float max_distance2, std::vector<Neighbour>& out,
                          Order order = Order::nearest_first);
    /// k_nearest over one mapped index.
    static void k_nearest(Mapped a, Vec3 p, int k, float max_distance2, std::vector<Neighbour>& out,
                          Order order = Order::nearest_first);

    /// The squared distance every search measures, the same bits wherever it is computed.
    static float distance2(Vec3 a, Vec3 p) {
        const float dx = a.x - p.x, dy = a.y - p.y, dz = a.z - p.z;
        return dx * dx + dy * dy + dz * dz;
    }

    /// Every point within sqrt(max_distance2) of `p`, in the order the search meets them (the
    /// same for every query of the same point and index).
    void within(Vec3 p, float max_distance2, std::vector<Neighbour>& out) const;
    /// within over the union of two mapped indexes.
    static void within(Mapped a, Mapped b, Vec3 p, float max_distance2, std::vector<Neighbour>& out);

private:
    /// A point and its index in the input, 16 bytes.
    struct Entry {
        float p[3];
        uint32_t id;
    };

    /// How far a query point lies from the cell of a range: per axis, and squared in all.
    struct CellDistance {
        float offset[3] = {0, 0, 0};
        float distance2 = 0;
    };

    /// An index over `points` whose point i answers as `ids[i]`.
    static PointIndex answering_as(const std::vector<Vec3>& points, const std::vector<uint32_t>& ids);
    void build(uint32_t begin, uint32_t end, Vec3 lower, Vec3 upper);
    /// Where the leaf whose cell holds p begins.
    uint32_t leaf_of(Vec3 p) const;
    /// Builds again, as trees of their own, the ranges within [begin, end) that updated()
    /// changed much (`removed_before[i]`: the points removed before position i).
    void rebuild_changed(uint32_t begin, uint32_t end, const std::vector<uint32_t>& removed_before);
    template <class Heap, class Ids>
    void search(uint32_t begin, uint32_t end, const float p[3], CellDistance cell, Heap& heap, Ids ids) const;
    /// Searches one part (index and ids) into `heap`.
    template <class Heap, class Part>
    static void search_part(const float p[3], Heap& heap, const Part& part);
    /// Searches each of `parts` into one heap, then moves its result to `out`; search_nearest
    /// keeps only the nearest, pruning from `known` on; search_within collects every point
    /// within the radius instead.
    template <class... Parts>
    static void search_all(Vec3 p, int k, float max_distance2, Order order, std::vector<Neighbour>& out,
                           Parts... parts);
    template <class... Parts>
    static std::optional<Neighbour> search_nearest(Vec3 p, float max_distance2, std::optional<Neighbour> known,
                                                   Parts... parts);
    template <class... Parts>
    static void search_within(Vec3 p, float max_distance2, std::vector<Neighbour>& out, Parts... parts);

    std::vector<Entry> m_entries;  // in tree order
    // A range [begin, end) longer than a leaf splits at mid = (begin + end) / 2 into [begin, mid)
    // (coordinates <= the split value) and [mid, end) (>=); its axis and value are kept at mid.
    std::vector<uint8_t> m_axis;
    std::vector<float> m_split;
    // Points added by updated(), grouped by leaf: those of the leaf [begin, end) are
    // m_added[m_added_first[begin] .. m_added_first[end]) (m_added_first: one per position and
    // one more; empty when none were).
    std::vector<Entry> m_added;
    std::vector<uint32_t> m_added_first;
    // Ranges updated() built again (marked in m_axis): their mids, ascending, and their trees.
    std::vector<uint32_t> m_rebuilt_mids;
    std::vector<PointIndex> m_rebuilt;
};

}  // namespace steadylight
