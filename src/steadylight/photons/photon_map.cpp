#include "steadylight/photons/photon_map.h"

#include <algorithm>
#include <cmath>
#include <thread>
#include <unordered_map>

#include "steadylight/base/check.h"
#include "steadylight/base/parallel.h"
#include "steadylight/base/rng.h"
#include "steadylight/base/settings_check.h"

namespace steadylight {
namespace {

std::vector<Vec3> positions_of(const std::vector<Photon>& photons) {
    std::vector<Vec3> positions;
    positions.reserve(photons.size());
    for (const Photon& photon : photons) positions.push_back(photon.p);
    return positions;
}

std::vector<Vec3> positions_of(const std::vector<Photon>& photons, const std::vector<uint32_t>& ids) {
    std::vector<Vec3> positions;
    positions.reserve(ids.size());
    for (const uint32_t id : ids) positions.push_back(photons[id].p);
    return positions;
}

/// The squared radius of an estimate that found `neighbours`.
float estimate_radius2(const std::vector<Neighbour>& neighbours, const DensitySettings& settings) {
    return int(neighbours.size()) < settings.k ? settings.max_radius * settings.max_radius
                                               : neighbours.back().distance2;
}

/// A disc of radius r around p (normal n), probed (`disc`): which photons on it an estimate counts.
struct ProbedDisc {
    Vec3 p, n;
    float r, r2;
    DiscProbes disc;
    const SurfaceCoverage& coverage;
    OrthonormalBasis basis = OrthonormalBasis::from_normal(n);

    /// Whether the estimate counts `photon`, found on the disc: arriving on n's side, and, in a
    /// cell whose probe missed the surface or in front of the disc's plane, reached by the surface.
    bool counts(const Photon& photon) const {
        if (!same_side(photon, n)) return false;
        const Vec3 offset = photon.p - p;
        bool untested = dot(offset, n) <= coverage_lift * r;
        if (untested && disc.share() < 1) {
            const Vec3 local = basis.to_local(offset);
            untested = disc.reached_cell(local.x, local.y, r2);
        }
        return untested || coverage.reaches(p, n, r, photon.p);
    }
    /// The irradiance a power summed over the disc gives: over its area on the surface (at least
    /// what one probe of 16 gives).
    Rgb irradiance(Rgb power) const { return power / (pi * r2 * std::max(disc.share(), 1.0f / 16)); }
};

}  // namespace

PhotonMap::PhotonMap(std::vector<Photon> photons, long emitted)
    : m_photons(std::move(photons)),
      m_emitted(emitted),
      m_index(std::make_shared<const PointIndex>(positions_of(m_photons))) {}

PhotonMap::PhotonMap(std::vector<Photon> photons, long emitted, const PhotonMap& base, const KeptStaticPhotons& kept)
    : m_photons(std::move(photons)), m_emitted(emitted), m_index(base.m_index) {
    SL_CHECK(!base.m_overlay && kept.frame_ids.size() == base.size());
    if (!m_index) m_index = std::make_shared<const PointIndex>();  // base is an empty map
    PointIndex added(positions_of(m_photons, kept.added_ids));
    std::vector<uint32_t> added_tree_ids = added.in_tree_order(kept.added_ids);
    m_overlay = std::make_shared<const Overlay>(
        Overlay{m_index->in_tree_order(kept.frame_ids), std::move(added_tree_ids), std::move(added)});
}

size_t PhotonMap::indexed_here() const { return m_overlay ? m_overlay->added.size() : m_photons.size(); }

void PhotonMap::k_nearest(Vec3 p, int k, float max_radius, std::vector<Neighbour>& out, PointIndex::Order order) const {
    if (!m_index) return out.clear();
    if (!m_overlay) return m_index->k_nearest(p, k, max_radius * max_radius, out, order);
    PointIndex::k_nearest({m_index.get(), m_overlay->base_ids.data()}, {&m_overlay->added, m_overlay->added_ids.data()},
                          p, k, max_radius * max_radius, out, order);
}

bool PhotonMap::k_nearest_from_base(Vec3 p, int k, float max_radius, const PhotonMap& base,
                                    const std::vector<uint32_t>& base_nearest, int base_k,
                                    const std::vector<uint32_t>& base_to_here, std::vector<Neighbour>& out) const {
    if (!m_overlay || k <= 0) return false;
    const float max_distance2 = max_radius * max_radius;
    // Every base photon nearer than the list's last is in it; beyond it, only a full list
    // leaves some out. Ids here keep the base's order, so the kept ones stay sorted.
    const bool complete = int(base_nearest.size()) < base_k;
    const float bound2 = complete ? max_distance2 : PointIndex::distance2(base.photons()[base_nearest.back()].p, p);
    thread_local std::vector<Neighbour> kept, added;
    kept.clear();
    for (const uint32_t base_id : base_nearest)
        if (const uint32_t id = base_to_here[base_id]; id != PointIndex::removed)
            kept.push_back({id, PointIndex::distance2(m_photons[id].p, p)});
    PointIndex::k_nearest({&m_overlay->added, m_overlay->added_ids.data()}, p, k, bound2, added);
    // The first k of the two lists merged, as the search's heap orders them.
    out.clear();
    size_t a = 0, b = 0;
    while (int(out.size()) < k && (a < kept.size() || b < added.size())) {
        const bool from_kept = b == added.size() || (a < kept.size() && nearer_neighbour(kept[a], added[b]));
        out.push_back(from_kept ? kept[a++] : added[b++]);
    }
    if (complete) return true;
    // A base photon beyond the list could come before the k-th only at the list's last distance
    // or further.
    return int(out.size()) == k && out.back().distance2 < bound2;
}

void PhotonMap::within(Vec3 p, float radius, std::vector<Neighbour>& out) const {
    if (!m_index) return out.clear();
    if (!m_overlay) return m_index->within(p, radius * radius, out);
    PointIndex::within({m_index.get(), m_overlay->base_ids.data()}, {&m_overlay->added, m_overlay->added_ids.data()}, p,
                       radius * radius, out);
}

Rgb PhotonMap::estimate_irradiance(Vec3 p, Vec3 n, const DensitySettings& settings, float* radius) const {
    thread_local std::vector<Neighbour> neighbours;
    k_nearest(p, settings.k, settings.max_radius, neighbours);
    const float r2 = estimate_radius2(neighbours, settings);
    if (radius) *radius = std::sqrt(r2);
    if (neighbours.empty()) return {};
    const size_t inside = int(neighbours.size()) < settings.k ? neighbours.size() : neighbours.size() - 1;
    Rgb sum;
    for (size_t j = 0; j < inside; ++j)
        if (same_side(m_photons[neighbours[j].index], n)) sum += m_photons[neighbours[j].index].power;
    return sum / (pi * r2);
}

Rgb PhotonMap::estimate_irradiance_on_surface(Vec3 p, Vec3 n, const DensitySettings& settings,
                                              const SurfaceCoverage& coverage, uint64_t seed, float* radius,
                                              DiscProbes* probes) const {
    thread_local std::vector<Neighbour> neighbours;
    k_nearest(p, settings.k, settings.max_radius, neighbours);
    return irradiance_on_surface(neighbours, p, n, settings, coverage, seed, radius, probes);
}

Rgb PhotonMap::irradiance_on_surface(const std::vector<Neighbour>& neighbours, Vec3 p, Vec3 n,
                                     const DensitySettings& settings, const SurfaceCoverage& coverage, uint64_t seed,
                                     float* radius, DiscProbes* probes) const {
    const float r2 = estimate_radius2(neighbours, settings), r = std::sqrt(r2);
    if (radius) *radius = r;
    if (probes) *probes = DiscProbes{};
    if (neighbours.empty()) return {};
    const ProbedDisc disc{p, n, r, r2, coverage.probes(p, n, r, coverage_lift * r, r, seed), coverage};
    if (probes) *probes = disc.disc;
    const size_t inside = int(neighbours.size()) < settings.k ? neighbours.size() : neighbours.size() - 1;
    Rgb sum;
    for (size_t j = 0; j < inside; ++j)
        if (const Photon& photon = m_photons[neighbours[j].index]; disc.counts(photon)) sum += photon.power;
    return disc.irradiance(sum);
}

Rgb PhotonMap::estimate_irradiance_cone(Vec3 p, Vec3 n, const DensitySettings& settings, float* radius) const {
    thread_local std::vector<Neighbour> neighbours;
    k_nearest(p, settings.k, settings.max_radius, neighbours);
    if (radius) *radius = settings.max_radius;
    if (neighbours.empty()) return {};
    const float r2 = estimate_radius2(neighbours, settings), r = std::sqrt(r2);
    if (radius) *radius = r;
    Rgb sum;
    for (const Neighbour& nb : neighbours)
        if (same_side(m_photons[nb.index], n)) sum += m_photons[nb.index].power * (1 - std::sqrt(nb.distance2) / r);
    return sum / ((1 - 2.0f / 3.0f) * pi * r2);
}

IrradiancePhotons::IrradiancePhotons(const PhotonMap& global, int stride, const DensitySettings& settings,
                                     SurfaceCoverage coverage, std::shared_ptr<const StaticIrradianceReuse> reuse)
    : m_global(&global), m_settings(settings), m_coverage(std::move(coverage)), m_reuse(std::move(reuse)) {
    static std::atomic<uint64_t> made = 0;
    m_id = ++made;
    SL_CHECK(stride >= 1);
    const std::vector<Photon>& photons = global.photons();
    struct Carrier {
        uint32_t photon;
        uint64_t hash;
        uint32_t static_carrier;  // or PointIndex::removed
    };
    std::vector<Carrier> carriers;
    // The photon's own hash: the same photon in the static map and in a frame's.
    const auto carrier_if_chosen = [&](uint32_t photon) {
        const uint64_t hash = hash_bits(photons[photon].p, photons[photon].wi);
        if (hash % uint64_t(stride) == 0) carriers.push_back({photon, hash, PointIndex::removed});
    };
    const IrradiancePhotons* from = m_reuse ? m_reuse->values : nullptr;
    if (from) {
        // A photon kept from the static map carries a value where its static photon does (the
        // same bits, the same hash): the static carriers kept, then the new photons chosen, put
        // in the frame's order.
        const KeptStaticPhotons& kept = m_reuse->kept;
        SL_CHECK(kept.frame_ids.size() == from->m_global->size());
        carriers.reserve(from->size() + kept.added_ids.size() / size_t(stride) * 17 / 16 + 16);
        for (uint32_t j = 0; j < from->size(); ++j)
            if (const uint32_t photon = kept.frame_ids[from->m_photon[j]]; photon != PointIndex::removed)
                carriers.push_back({photon, from->m_hash[j], j});
        const long kept_count = long(carriers.size());
        for (const uint32_t photon : kept.added_ids) carrier_if_chosen(photon);
        const auto by_photon = [](const Carrier& a, const Carrier& b) { return a.photon < b.photon; };
        const auto kept_end = carriers.begin() + kept_count;
        if (!std::is_sorted(carriers.begin(), kept_end, by_photon)) std::sort(carriers.begin(), kept_end, by_photon);
        std::inplace_merge(carriers.begin(), kept_end, carriers.end(), by_photon);
    } else {
        carriers.reserve(photons.size() / size_t(stride) * 17 / 16 + 16);
        for (uint32_t i = 0; i < photons.size(); ++i) carrier_if_chosen(i);
    }
    m_photon.resize(carriers.size()), m_hash.resize(carriers.size()), m_n.resize(carriers.size());
    if (from) m_static_carrier.resize(carriers.size());
    for (size_t i = 0; i < carriers.size(); ++i) {
        m_photon[i] = carriers[i].photon;
        m_hash[i] = carriers[i].hash;
        m_n[i] = photons[carriers[i].photon].n;
        if (from) m_static_carrier[i] = carriers[i].static_carrier;
    }
    m_values.resize(m_photon.size());
    m_state = std::make_unique<std::atomic<uint8_t>[]>(m_photon.size());  // value-initialised: all empty
    if (!m_reuse) {                                                       // values a frame's may read lists from
        m_wider.resize(m_photon.size());
        m_wider_state = std::make_unique<std::atomic<uint8_t>[]>(m_photon.size());
    }
    if (!from) {
        std::vector<Vec3> positions(m_photon.size());
        for (size_t i = 0; i < m_photon.size(); ++i) positions[i] = photons[m_photon[i]].p;
        m_index = PointIndex(positions);
        return;
    }
    // The static values' index with the values the frame lost taken out and its new ones filed
    // in: the same answers as an index built over this frame's values, without building one.
    std::vector<uint32_t> ids_by_static(from->size(), PointIndex::removed), added_ids;
    std::vector<Vec3> added;
    for (uint32_t i = 0; i < m_photon.size(); ++i)
        if (m_static_carrier[i] != PointIndex::removed) {
            ids_by_static[m_static_carrier[i]] = i;
        } else {
            added.push_back(photons[m_photon[i]].p);
            added_ids.push_back(i);
        }
    m_index = from->m_index.updated(ids_by_static, added, added_ids);
}

std::optional<IrradiancePhotons::Value> IrradiancePhotons::reused_value(uint32_t i, bool& carried) const {
    carried = false;
    if (!m_reuse) return std::nullopt;
    const uint32_t j = m_static_carrier[i];
    if (j == PointIndex::removed) return std::nullopt;  // a new photon
    Value value = m_reuse->values->value(j);
    const Photon& photon = m_global->photons()[m_photon[i]];
    // A dynamic object its probes may meet changes the disc.
    const float extent = coverage_probe_extent(photon.p, value.radius);
    for (const BoundingSphere& object : m_reuse->dynamic)
        if (!object.empty() && length(object.center - photon.p) <= object.radius + extent) return std::nullopt;
    // So does a photon removed or added within its radius (a little beyond: rounding): to be
    // carried, all of them; to tell that the value must be estimated again, one.
    const bool carry = m_reuse->changed_values == ChangedValues::carried && m_coverage;
    const float reach2 = value.radius * value.radius * 1.0001f + 1e-30f;
    thread_local std::vector<Neighbour> changes;
    if (carry)
        m_reuse->changed.within(photon.p, reach2, changes);
    else
        m_reuse->changed.k_nearest(photon.p, 1, reach2, changes);
    if (changes.empty()) return value;
    if (!carry) return std::nullopt;
    // Carried: the fixed-radius estimate on the static disc over the frame's photons is the
    // static one plus the power of the changes on the disc, summed in their order.
    std::sort(changes.begin(), changes.end(), [](const Neighbour& a, const Neighbour& b) { return a.index < b.index; });
    const float r2 = value.radius * value.radius;
    const ProbedDisc disc{photon.p, photon.n, value.radius, r2, value.probes, m_coverage};
    Rgb change;
    for (const Neighbour& found : changes)
        if (const Photon& changed = m_reuse->changes[found.index]; found.distance2 < r2 && disc.counts(changed))
            change += changed.power;
    const Rgb E = value.E + disc.irradiance(change);
    value.E = {std::max(0.0f, E.r), std::max(0.0f, E.g), std::max(0.0f, E.b)};  // rounding, when all went
    carried = true;
    return value;
}

const std::vector<uint32_t>& IrradiancePhotons::wider_nearest(uint32_t i) const {
    enum : uint8_t { empty, writing, ready };
    SL_CHECK(m_wider_state);
    if (m_wider_state[i].load(std::memory_order_acquire) == ready) return m_wider[i];
    thread_local std::vector<Neighbour> found;
    m_global->k_nearest(m_global->photons()[m_photon[i]].p, m_settings.k + wider_margin, m_settings.max_radius, found);
    std::vector<uint32_t> nearest(found.size());
    for (size_t j = 0; j < found.size(); ++j) nearest[j] = found[j].index;
    uint8_t expected = empty;
    if (m_wider_state[i].compare_exchange_strong(expected, writing, std::memory_order_acquire)) {
        m_wider[i] = std::move(nearest);
        m_wider_state[i].store(ready, std::memory_order_release);
        return m_wider[i];
    }
    while (m_wider_state[i].load(std::memory_order_acquire) != ready) std::this_thread::yield();
    return m_wider[i];
}

bool IrradiancePhotons::nearest_from_static(uint32_t i, std::vector<Neighbour>& out) const {
    if (!m_reuse || m_reuse->changed_values != ChangedValues::carried) return false;
    const uint32_t j = m_static_carrier[i];
    if (j == PointIndex::removed) return false;  // a new photon
    const IrradiancePhotons& from = *m_reuse->values;
    return m_global->k_nearest_from_base(m_global->photons()[m_photon[i]].p, m_settings.k, m_settings.max_radius,
                                         *from.m_global, from.wider_nearest(j), m_settings.k + wider_margin,
                                         m_reuse->kept.frame_ids, out);
}

const IrradiancePhotons::Value& IrradiancePhotons::value(uint32_t i) const {
    enum : uint8_t { empty, writing, ready };
    if (m_state[i].load(std::memory_order_acquire) == ready) return m_values[i];
    // A pure function of the map: whichever thread computes it first, the value is the same.
    bool carried = false;
    const std::optional<Value> reused = reused_value(i, carried);
    thread_local std::vector<Neighbour> nearest;
    Value value;
    if (reused) {
        value = *reused;
    } else if (m_coverage && nearest_from_static(i, nearest)) {
        const Photon& photon = m_global->photons()[m_photon[i]];
        value.E = m_global->irradiance_on_surface(nearest, photon.p, photon.n, m_settings, m_coverage, m_hash[i],
                                                  &value.radius, &value.probes);
        m_from_static_lists.fetch_add(1, std::memory_order_relaxed);
    } else {
        const Photon& photon = m_global->photons()[m_photon[i]];
        value.E = m_coverage ? m_global->estimate_irradiance_on_surface(photon.p, photon.n, m_settings, m_coverage,
                                                                        m_hash[i], &value.radius, &value.probes)
                             : m_global->estimate_irradiance(photon.p, photon.n, m_settings, &value.radius);
    }
    uint8_t expected = empty;
    if (m_state[i].compare_exchange_strong(expected, writing, std::memory_order_acquire)) {
        m_values[i] = value;
        m_state[i].store(ready, std::memory_order_release);
        (carried ? m_carried : reused ? m_reused : m_computed).fetch_add(1, std::memory_order_relaxed);
        return m_values[i];
    }
    // Another thread is writing the same value: wait for it.
    while (m_state[i].load(std::memory_order_acquire) != ready) std::this_thread::yield();
    return m_values[i];
}

void IrradiancePhotons::compute_all() const {
    parallel_for_chunks(long(m_values.size()), 256, [&](long begin, long end) {
        for (long i = begin; i < end; ++i) value(uint32_t(i));
    });
}

std::optional<Rgb> IrradiancePhotons::lookup(Vec3 p, Vec3 n, float max_radius) const {
    // The value of the first of `neighbours` (nearest first) whose normal agrees and whose disc
    // the surface at p reaches.
    const auto first_agreeing = [&](const std::vector<Neighbour>& neighbours) -> std::optional<Rgb> {
        for (const Neighbour& nb : neighbours) {
            if (!same_side(m_n[nb.index], n)) continue;
            const Value& value = this->value(nb.index);
            const float radius = value.radius;
            const DiscProbes& disc = value.probes;
            if (!m_coverage) return value.E;
            // Untested when p lies on the photon's surface as its own estimate saw it: within
            // its disc, in a cell its surface reaches, and the photon not in front of p's plane.
            const Photon& photon = m_global->photons()[m_photon[nb.index]];
            const float distance = std::sqrt(nb.distance2);
            bool untested = nb.distance2 < radius * radius && dot(photon.p - p, n) <= coverage_lift * distance;
            if (untested && disc.share() < 1) {
                const Vec3 local = OrthonormalBasis::from_normal(photon.n).to_local(p - photon.p);
                untested = disc.reached_cell(local.x, local.y, radius * radius);
            }
            if (untested || m_coverage.reaches(p, n, distance, photon.p)) return value.E;
        }
        return std::nullopt;
    };
    // Most look-ups are answered by the single nearest photon; only near creases and thin walls
    // does its normal disagree, and then the next few are tried.
    thread_local std::vector<Neighbour> neighbours;
    // A thread's look-ups come in runs of nearby points (a record's gather rays, in the order of
    // their directions): the last one's answer bounds the next one's search.
    thread_local struct {
        uint64_t of = 0;
        uint32_t value = 0;
    } last;
    const float max_distance2 = max_radius * max_radius;
    std::optional<Neighbour> known;
    if (last.of == m_id) {
        const float distance2 = PointIndex::distance2(m_global->photons()[m_photon[last.value]].p, p);
        if (distance2 <= max_distance2) known = Neighbour{last.value, distance2};
    }
    const std::optional<Neighbour> nearest = m_index.nearest(p, max_distance2, known);
    if (!nearest) return std::nullopt;  // nothing within reach
    last = {m_id, nearest->index};
    neighbours.assign(1, *nearest);
    if (const std::optional<Rgb> E = first_agreeing(neighbours)) return E;
    m_index.k_nearest(p, 8, max_distance2, neighbours);
    return first_agreeing(neighbours);
}

std::shared_ptr<const StaticIrradianceReuse> make_static_irradiance_reuse(
    const IrradiancePhotons& values, const PhotonMap& static_map, const PhotonMap& frame_map, KeptStaticPhotons kept,
    ChangedValues changed_values, std::vector<BoundingSphere> dynamic) {
    SL_CHECK_EQ(kept.frame_ids.size(), static_map.size());
    auto reuse = std::make_shared<StaticIrradianceReuse>();
    reuse->values = &values;
    for (size_t i = 0; i < static_map.size(); ++i) {
        if (kept.frame_ids[i] != PointIndex::removed) continue;
        Photon removed = static_map.photons()[i];
        removed.power = removed.power * -1.0f;  // exact
        reuse->changes.push_back(removed);
    }
    for (const uint32_t i : kept.added_ids) reuse->changes.push_back(frame_map.photons()[i]);
    reuse->changed = PointIndex(positions_of(reuse->changes));
    reuse->kept = std::move(kept);
    reuse->changed_values = changed_values;
    reuse->dynamic = std::move(dynamic);
    return reuse;
}

KeptStaticPhotons kept_static_photons_by_bits(const PhotonMap& frame_map, const PhotonMap& static_map) {
    // Static photons by their bits, equal ones in order; each frame photon takes the first left.
    const auto bits_hash = [](const Photon& photon) { return hash_bits(photon.p, photon.wi); };
    std::unordered_multimap<uint64_t, uint32_t> by_hash;
    by_hash.reserve(static_map.size());
    for (size_t i = 0; i < static_map.size(); ++i) by_hash.emplace(bits_hash(static_map.photons()[i]), uint32_t(i));
    KeptStaticPhotons kept;
    kept.frame_ids.assign(static_map.size(), PointIndex::removed);
    for (size_t i = 0; i < frame_map.size(); ++i) {
        const Photon& photon = frame_map.photons()[i];
        const auto [first, last] = by_hash.equal_range(bits_hash(photon));
        uint32_t best = PointIndex::removed;
        for (auto it = first; it != last; ++it)
            if (kept.frame_ids[it->second] == PointIndex::removed &&
                same_bits(static_map.photons()[it->second], photon) && it->second < best)
                best = it->second;
        if (best == PointIndex::removed)
            kept.added_ids.push_back(uint32_t(i));
        else
            kept.frame_ids[best] = uint32_t(i);
    }
    return kept;
}

bool same_photons(const PhotonMap& a, const PhotonMap& b) {
    return a.size() == b.size() && std::equal(a.photons().begin(), a.photons().end(), b.photons().begin(),
                                              [](const Photon& x, const Photon& y) { return same_bits(x, y); });
}

void validate(const DensitySettings& settings, const std::string& where) {
    check_setting_range(where + "/k", settings.k, 2, 1'000'000);  // the k-th only marks the radius
    check_setting_range(where + "/max_radius", settings.max_radius, 1e-6f, 1e30f);
}

}  // namespace steadylight
