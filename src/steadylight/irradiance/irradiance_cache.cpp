// The irradiance cache: records in insertion order plus a spatial index over their spheres of
// validity, Ward's weighted interpolation with gradients, and neighbour clamping. The index is a
// hierarchical hash grid rather than an octree: it needs no scene bounds, and each look-up is one
// hash probe per level in use, in a fixed order, so results are deterministic.
#include "steadylight/irradiance/irradiance_cache.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "steadylight/base/check.h"
#include "steadylight/base/ray.h"  // infinity
#include "steadylight/base/rng.h"
#include "steadylight/base/settings_check.h"

namespace steadylight {
namespace {

// Widens indexed spheres slightly so float rounding in the weight test never finds a record
// outside the sphere it was indexed with.
constexpr float index_padding = 1.0001f;
/// Relaxed look-ups let records reach up to this multiple of their reach.
constexpr float max_reach_scale = 2.0f;

// Ward's test against records "in front of" p (Ward, Rubinstein & Clear 1988): tolerance
// as a fraction of the record's radius, so flat and gently curved surfaces never trip it.
constexpr float in_front_tolerance = 0.05f;

constexpr float sqrt_half = 0.70710678f;

/// A hierarchical hash grid over spheres. A sphere of radius r lives at the level whose cells are
/// the smallest power of two >= 2r, in every cell its bounding box overlaps (at most 8), so at each
/// level in use the one cell containing a point lists every sphere that may contain that point.
/// A cell keeps its spheres' centres beside their ids, with a radius of the caller's, so that a
/// look-up's first test reads the cell's bytes, not the records'. Look-ups come in runs of nearby
/// points (a tile's pixels), which mostly fall in cells found a moment before: each thread
/// remembers the last eight cells it found per level, for the grid as it was then (its generation).
class SphereGrid {
public:
    struct Entry {
        Vec3 center;
        float kept;  // the caller's radius, which the grid does not read
        uint32_t id;
    };

    SphereGrid() : m_generation(next_generation()) {}

    /// Indexes sphere `id` at `center` with radius `radius`, keeping `kept` beside it.
    void insert(uint32_t id, Vec3 center, float radius, float kept) {
        int level = 0;
        std::frexp(2 * radius, &level);  // 2r = m 2^level, m in [0.5, 1): cells of 2^level >= 2r
        level = std::max(level, min_level);
        const auto lo = cell_of(center - Vec3{radius, radius, radius}, level);
        const auto hi = cell_of(center + Vec3{radius, radius, radius}, level);
        for (int64_t z = lo[2]; z <= hi[2]; ++z)
            for (int64_t y = lo[1]; y <= hi[1]; ++y)
                for (int64_t x = lo[0]; x <= hi[0]; ++x) {
                    const Key key{level, x, y, z};
                    const auto [cell, added] = m_cells.try_emplace(key);
                    cell->second.push_back({center, kept, id});
                    if (added) mark_occupied(key);
                }
        if (!std::binary_search(m_levels.begin(), m_levels.end(), level))
            m_levels.insert(std::upper_bound(m_levels.begin(), m_levels.end(), level), level);
        m_generation = next_generation();
    }

    /// Calls `f(entry)` once for every sphere that may contain `p` (and perhaps a few more).
    template <class F>
    void for_each_candidate(Vec3 p, F&& f) const {
        for (size_t k = 0; k < m_levels.size(); ++k) {
            const auto c = cell_of(p, m_levels[k]);
            const Key key{m_levels[k], c[0], c[1], c[2]};
            if (const std::vector<Entry>* cell = memo_of(k).cell(*this, key))
                for (const Entry& entry : *cell) f(entry);
        }
    }

    void clear() {
        m_cells.clear();
        m_occupied.clear();
        m_levels.clear();
        m_generation = next_generation();
    }

private:
    // Cells no smaller than 2^-32 world units keep cell coordinates well inside int64.
    static constexpr int min_level = -32;

    struct Key {
        int level;
        int64_t x, y, z;
        bool operator==(const Key&) const = default;
    };
    struct KeyHash {
        size_t operator()(const Key& k) const {
            return size_t(hash_ids(uint64_t(int64_t(k.level)), uint64_t(k.x), uint64_t(k.y), uint64_t(k.z)));
        }
    };
    /// The cells a thread found last at one level of a grid, as the grid was (its generation).
    /// A tile's row of pixels crosses several cells of the finest level, and the rows below it
    /// cross the same ones. Counted at 1280x960 (a cell spans about four pixels), a frame's
    /// look-ups missed 0.9 times each with four cells kept and 0.67 times with eight, nearly all
    /// of them at empty cells, which may_be_occupied answers.
    class Memo {
    public:
        /// Cell `key` of `grid` (nullptr: none), from the memo or found and remembered.
        const std::vector<Entry>* cell(const SphereGrid& grid, const Key& key) {
            if (m_generation != grid.m_generation) m_generation = grid.m_generation, m_kept = 0;
            for (int i = 0; i < m_kept; ++i)
                if (m_keys[size_t(i)] == key) return m_cells[size_t(i)];
            const std::vector<Entry>* cell = nullptr;
            if (grid.may_be_occupied(key))
                if (const auto it = grid.m_cells.find(key); it != grid.m_cells.end()) cell = &it->second;
            const size_t slot = m_kept < size ? size_t(m_kept++) : m_next++ % size;
            m_keys[slot] = key, m_cells[slot] = cell;
            return cell;
        }

    private:
        static constexpr int size = 8;
        uint64_t m_generation = 0;  // none: generations start at 1
        int m_kept = 0;
        size_t m_next = 0;  // the slot to replace next once all are kept
        std::array<Key, size> m_keys;
        std::array<const std::vector<Entry>*, size> m_cells;
    };

    /// Every grid and every change to one gets a new generation, so that a memo never outlives
    /// what it points into.
    static uint64_t next_generation() {
        static std::atomic<uint64_t> last = 0;
        return ++last;
    }
    /// This thread's memo for level k of this grid: sixteen grids' (a frame's caches are read in
    /// turns) by their generation, eight levels each (further levels share the last slot).
    Memo& memo_of(size_t k) const {
        constexpr size_t grids = 16, levels = 8;
        thread_local std::array<Memo, grids * levels> memos;
        return memos[(m_generation % grids) * levels + std::min(k, levels - 1)];
    }

    /// Whether cell `key` may hold spheres: one bit per hash of the occupied cells' keys, at
    /// least eight bits per cell. Most cells a look-up probes are empty (the finer levels are in
    /// use elsewhere in the scene: 95% of the probes the memo missed at 1280x960), and a bit
    /// costs less than a probe of the hash table.
    bool may_be_occupied(const Key& key) const {
        if (m_occupied.empty()) return false;
        const uint64_t bit = occupancy_hash(key) >> m_occupied_shift;
        return (m_occupied[bit / 64] >> (bit % 64)) & 1;
    }
    void mark_occupied(const Key& key) {
        if (m_cells.size() * 8 > m_occupied.size() * 64) {
            // Twice the bits the cells need now, the keys' bits set again.
            const int bits = std::max(int(std::bit_width(m_cells.size() * 16 - 1)), 10);
            m_occupied.assign(size_t(1) << (bits - 6), 0);
            m_occupied_shift = 64 - bits;
            for (const auto& [cell, entries] : m_cells) set_occupied(cell);
        } else {
            set_occupied(key);
        }
    }
    void set_occupied(const Key& key) {
        const uint64_t bit = occupancy_hash(key) >> m_occupied_shift;
        m_occupied[bit / 64] |= uint64_t(1) << (bit % 64);
    }
    /// A cheap hash whose top bits depend on every bit of the key (what may_be_occupied reads).
    static uint64_t occupancy_hash(const Key& k) {
        const uint64_t h = uint64_t(k.x) * 0x9E3779B97F4A7C15ull ^ uint64_t(k.y) * 0xC2B2AE3D27D4EB4Full ^
                           uint64_t(k.z) * 0x165667B19E3779F9ull ^ uint64_t(int64_t(k.level)) * 0x27D4EB2F165667C5ull;
        return (h ^ (h >> 31)) * 0x94D049BB133111EBull;
    }

    static std::array<int64_t, 3> cell_of(Vec3 p, int level) {
        const float inverse_size = std::ldexp(1.0f, -level);  // a power of two: exact, monotonic
        return {int64_t(std::floor(p.x * inverse_size)), int64_t(std::floor(p.y * inverse_size)),
                int64_t(std::floor(p.z * inverse_size))};
    }

    std::unordered_map<Key, std::vector<Entry>, KeyHash> m_cells;
    std::vector<uint64_t> m_occupied;  // may_be_occupied's bits
    int m_occupied_shift = 64;
    std::vector<int> m_levels;  // sorted
    uint64_t m_generation;
};

/// Ward's weight of `record` at (p, n): 1 / (|p - p_i| / R_i + sqrt(1 - n . n_i)), infinite at the
/// record itself; 0 when the record must not be used there (normals apart, or record in front).
float ward_weight(const IrradianceRecord& record, Vec3 p, Vec3 n) {
    const float cos_normals = dot(n, record.n);
    if (cos_normals <= 0) return 0;
    const Vec3 offset = p - record.p;
    if (dot(offset, (n + record.n) * 0.5f) < -in_front_tolerance * record.radius) return 0;
    // sqrt(1 - n . n_i) = |n - n_i| / sqrt(2) for unit normals; the difference stays exact as n_i
    // approaches n, where 1 - n . n_i rounds to about 1e-7 and its root to about 3e-4.
    const float error = length(offset) / record.radius + length(n - record.n) * sqrt_half;
    return error > 0 ? 1 / error : infinity;
}

/// How much of record's translational gradient extrapolate() applies, per channel. Near contact
/// geometry (a crease where a wall meets the floor, the foot of a ball) translational gradients
/// grow like 1 / (nearest distance), and a record carries them far past where they hold (dark and
/// light specks along creases: docs/notes/truth-gradient-specks.md). Over its radius a record's
/// translational change may be at most its own E (Tabellion and Lamorlette 2004 limit the radius
/// to R <= E / |grad E|; here the radius also serves the spacing and neighbour clamps, so the
/// gradient is scaled to E / R instead). A function of the record alone, kept beside it: a
/// look-up would otherwise take three square roots and divisions per record it uses.
std::array<float, 3> gradient_scales(const IrradianceRecord& record) {
    std::array<float, 3> scales;
    for (int c = 0; c < 3; ++c) {
        const float change_over_radius = length(record.translational_gradient[size_t(c)]) * record.radius;
        scales[size_t(c)] = change_over_radius > record.E[c] ? record.E[c] / change_over_radius : 1.0f;
    }
    return scales;
}

/// The record's irradiance carried to (p, n) by its gradients, the translational one scaled by
/// `scales` (gradient_scales), the whole change within [0, 2 E].
Rgb extrapolate(const IrradianceRecord& record, const std::array<float, 3>& scales, Vec3 p, Vec3 n) {
    const Vec3 turn = cross(record.n, n), move = p - record.p;
    const auto channel = [&](int c) {
        const float change = dot(turn, record.rotational_gradient[size_t(c)]) +
                             dot(move, record.translational_gradient[size_t(c)]) * scales[size_t(c)];
        return record.E[c] + std::clamp(change, -record.E[c], record.E[c]);
    };
    return {channel(0), channel(1), channel(2)};
}

struct WeightedRecord {
    uint32_t id;
    float weight;
};

/// The records whose weight at (p, n) exceeds 1 / accuracy, in insertion order. The result lives
/// in a per-thread buffer, valid until the thread's next call: look-ups allocate nothing.
const std::vector<WeightedRecord>& usable_records(const SphereGrid& index, const std::vector<IrradianceRecord>& records,
                                                  float accuracy, Vec3 p, Vec3 n) {
    thread_local std::vector<WeightedRecord> used;
    used.clear();
    index.for_each_candidate(p, [&](const SphereGrid::Entry& candidate) {
        // w_i > 1 / a needs |p - p_i| < a R_i: most candidates fail this cheap test (the grid
        // keeps each record's p_i and R_i).
        const float reach = accuracy * candidate.kept;
        if (length2(p - candidate.center) >= reach * reach) return;
        const float weight = ward_weight(records[candidate.id], p, n);
        if (weight > 1 / accuracy) used.push_back({candidate.id, weight});
    });
    std::sort(used.begin(), used.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
    return used;
}

/// The ids of `used`, in its order.
void ids_of(const std::vector<WeightedRecord>& used, std::vector<uint32_t>& out) {
    out.resize(used.size());
    for (size_t i = 0; i < used.size(); ++i) out[i] = used[i].id;
}

/// Ward's interpolation at (p, n) over `used`, the records usable there with their weights.
Rgb weighted_sum(const std::vector<IrradianceRecord>& records, const std::vector<std::array<float, 3>>& scales,
                 const std::vector<WeightedRecord>& used, Vec3 p, Vec3 n) {
    // Scale weights by the largest, so that at a record's own position (infinite weight) only
    // that record counts and its E comes back exactly.
    float max_weight = 0;
    for (const WeightedRecord& r : used) max_weight = std::max(max_weight, r.weight);
    Rgb sum;
    float weight_sum = 0;
    for (const WeightedRecord& r : used) {
        const float weight = max_weight == infinity ? (r.weight == infinity ? 1.0f : 0.0f) : r.weight / max_weight;
        if (weight == 0) continue;
        sum += extrapolate(records[r.id], scales[r.id], p, n) * weight;
        weight_sum += weight;
    }
    return sum / weight_sum;
}

}  // namespace

/// The records' spheres of reach twice: as far as a look-up reaches, and as far as a relaxed one
/// does. A cell holds records whose spheres overlap it, most of which do not reach a given point
/// in it; cells sized for the look-ups' own reach hold a quarter as many on a surface.
struct IrradianceCache::Index {
    SphereGrid reach, relaxed_reach;

    void insert(uint32_t id, const IrradianceRecord& record, float accuracy) {
        reach.insert(id, record.p, accuracy * record.radius * index_padding, record.radius);
        relaxed_reach.insert(id, record.p, max_reach_scale * accuracy * record.radius * index_padding, record.radius);
    }
    /// usable_records at (p, n) for a look-up reaching `reach_scale` times as far as Ward's
    /// (clamped to [1, max_reach_scale]).
    const std::vector<WeightedRecord>& usable(const std::vector<IrradianceRecord>& records, float accuracy, Vec3 p,
                                              Vec3 n, float reach_scale) const {
        const float scale = std::clamp(reach_scale, 1.0f, max_reach_scale);
        return usable_records(scale <= 1 ? reach : relaxed_reach, records, accuracy * scale, p, n);
    }
    void clear() {
        reach.clear();
        relaxed_reach.clear();
    }
};

IrradianceCache::IrradianceCache(CacheSettings settings) : IrradianceCache(settings, std::make_shared<Index>()) {}
IrradianceCache::IrradianceCache(CacheSettings settings, std::shared_ptr<Index> index)
    : m_settings(settings), m_index(std::move(index)) {
    SL_CHECK(settings.accuracy > 0);
}
IrradianceCache::~IrradianceCache() = default;
IrradianceCache::IrradianceCache(IrradianceCache&&) noexcept = default;
IrradianceCache& IrradianceCache::operator=(IrradianceCache&&) noexcept = default;

void IrradianceCache::insert(const IrradianceRecord& record) {
    SL_CHECK(record.radius > 0 && std::isfinite(record.radius));
    SL_CHECK_EQ(m_index.use_count(), 1);  // not shared with_irradiance
    // w_i > 1 / a needs |p - p_i| < a R_i: that is the sphere to index.
    m_index->insert(uint32_t(m_records.size()), record, m_settings.accuracy);
    m_records.push_back(record);
    m_gradient_scales.emplace_back();
    set_derived(m_records.size() - 1);
}

void IrradianceCache::set_derived(size_t i) { m_gradient_scales[i] = gradient_scales(m_records[i]); }

IrradianceCache IrradianceCache::with_irradiance(std::vector<IrradianceRecord> records) const {
    SL_CHECK_EQ(records.size(), m_records.size());
    for (size_t i = 0; i < records.size(); ++i)
        SL_CHECK(records[i].p == m_records[i].p && records[i].n == m_records[i].n &&
                 records[i].radius == m_records[i].radius);
    IrradianceCache out(m_settings, m_index);
    out.m_records = std::move(records);
    out.m_gradient_scales.resize(out.m_records.size());
    for (size_t i = 0; i < out.m_records.size(); ++i) out.set_derived(i);
    return out;
}

std::optional<Rgb> IrradianceCache::interpolate(Vec3 p, Vec3 n, float reach_scale,
                                                std::vector<uint32_t>* used_ids) const {
    const std::vector<WeightedRecord>& used = m_index->usable(m_records, m_settings.accuracy, p, n, reach_scale);
    if (used_ids) ids_of(used, *used_ids);
    if (used.empty()) return std::nullopt;
    return weighted_sum(m_records, m_gradient_scales, used, p, n);
}

void IrradianceCache::usable_ids(Vec3 p, Vec3 n, float reach_scale, std::vector<uint32_t>& out) const {
    ids_of(m_index->usable(m_records, m_settings.accuracy, p, n, reach_scale), out);
}

Rgb IrradianceCache::interpolate_over(std::span<const uint32_t> ids, Vec3 p, Vec3 n) const {
    SL_CHECK(!ids.empty());
    // The weights usable_records gave these records: the same function of the same record.
    thread_local std::vector<WeightedRecord> used;
    used.resize(ids.size());
    for (size_t i = 0; i < ids.size(); ++i) used[i] = {ids[i], ward_weight(m_records[ids[i]], p, n)};
    return weighted_sum(m_records, m_gradient_scales, used, p, n);
}

bool IrradianceCache::covers(Vec3 p, Vec3 n) const {
    bool found = false;
    m_index->reach.for_each_candidate(p, [&](const SphereGrid::Entry& candidate) {
        found = found || ward_weight(m_records[candidate.id], p, n) > 1 / m_settings.accuracy;
    });
    return found;
}

void IrradianceCache::clamp_radii_to_neighbours() {
    // Index the spheres of radius R_i: record j can lower R_i only if R_j + |p_i - p_j| < R_i,
    // which needs p_j inside that sphere.
    SphereGrid spheres;
    for (size_t i = 0; i < m_records.size(); ++i)
        spheres.insert(uint32_t(i), m_records[i].p, m_records[i].radius * index_padding, m_records[i].radius);

    // Lower each radius against the old radii of its neighbours. One such pass reaches the fixed
    // point (R_i = min_j R_j + |p_i - p_j| already satisfies the triangle inequality), and a min
    // does not depend on the order in which neighbours are visited.
    std::vector<float> radius(m_records.size());
    for (size_t i = 0; i < m_records.size(); ++i) radius[i] = m_records[i].radius;
    for (size_t j = 0; j < m_records.size(); ++j) {
        spheres.for_each_candidate(m_records[j].p, [&](const SphereGrid::Entry& candidate) {
            const uint32_t i = candidate.id;
            radius[i] = std::min(radius[i], m_records[j].radius + length(m_records[i].p - m_records[j].p));
        });
    }

    // Store the new radii and re-index the records' (now smaller) spheres of validity.
    SL_CHECK_EQ(m_index.use_count(), 1);  // not shared with_irradiance
    m_index->clear();
    for (size_t i = 0; i < m_records.size(); ++i) {
        m_records[i].radius = radius[i];
        set_derived(i);
        m_index->insert(uint32_t(i), m_records[i], m_settings.accuracy);
    }
}

const std::vector<IrradianceRecord>& IrradianceCache::records() const { return m_records; }
const CacheSettings& IrradianceCache::settings() const { return m_settings; }

float clamp_radius(float harmonic_mean_distance, float pixel_footprint, const CacheSettings& settings) {
    // A record reaches a * R (Ward's weight exceeds 1/a there), so the spacing limits, which are
    // about how far records reach in pixels, bound R at spacing / a.
    const float min_radius = settings.min_spacing_px * pixel_footprint / settings.accuracy;
    const float max_radius = settings.max_spacing_px * pixel_footprint / settings.accuracy;
    return std::min(std::max(harmonic_mean_distance, min_radius), max_radius);
}

void validate(const CacheSettings& settings, const std::string& where) {
    check_setting_range(where + "/accuracy", settings.accuracy, 0.01f, 2.0f);
    check_setting_range(where + "/min_spacing_px", settings.min_spacing_px, 0.5f, 1000.0f);
    check_setting_range(where + "/max_spacing_px", settings.max_spacing_px, 1.0f, 10000.0f);
    check_setting(settings.min_spacing_px <= settings.max_spacing_px, where + "/max_spacing_px",
                  "must not be smaller than min_spacing_px (--cache-max-spacing, --cache-spacing)");
}

}  // namespace steadylight
