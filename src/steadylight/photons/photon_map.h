// Photon maps (Jensen 2001): the photons of one kind (global, caustic, dynamic) in a kd-tree,
// with the density estimates that read them, and the irradiance precomputed at a subset of the
// global photons (Christensen 1999) so that a final-gather ray costs one nearest look-up.
#pragma once

#include <atomic>
#include <bit>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "steadylight/base/bounding_sphere.h"
#include "steadylight/base/ray.h"
#include "steadylight/photons/photon.h"
#include "steadylight/photons/point_index.h"
#include "steadylight/photons/surface_coverage.h"

namespace steadylight {

struct DensitySettings {
    int k = 64;               // photons per estimate
    float max_radius = 0.5f;  // scene units; estimates never look further
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(DensitySettings, k, max_radius)
void validate(const DensitySettings& settings, const std::string& where);

/// Which photons of a frame's map are the static map's, kept: per static photon, its photon in
/// the frame's map (or PointIndex::removed); and the frame's photons that are none of them
/// (new), ascending.
struct KeptStaticPhotons {
    std::vector<uint32_t> frame_ids;
    std::vector<uint32_t> added_ids;
};

class PhotonMap {
public:
    PhotonMap() = default;
    /// `emitted` is the number of photon paths the photons came from (for statistics).
    PhotonMap(std::vector<Photon> photons, long emitted);
    /// A map of `base`'s photons with some of them removed and others added, without indexing
    /// them all again: base photon i is `photons[kept.frame_ids[i]]` (or gone:
    /// PointIndex::removed), the added ones are `photons[kept.added_ids[j]]`, and the ids keep
    /// base's order. Look-ups search base's index and a small one of the added photons and
    /// answer exactly as a map built over `photons` would. `base` must be a map of its own (not
    /// composed like this).
    PhotonMap(std::vector<Photon> photons, long emitted, const PhotonMap& base, const KeptStaticPhotons& kept);

    const std::vector<Photon>& photons() const { return m_photons; }
    size_t size() const { return m_photons.size(); }
    long emitted() const { return m_emitted; }

    /// The k nearest photons to `p` within `max_radius`, nearest first.
    void k_nearest(Vec3 p, int k, float max_radius, std::vector<Neighbour>& out,
                   PointIndex::Order order = PointIndex::Order::nearest_first) const;
    /// k_nearest of a composed map from what its base knows: `base_nearest`, the ids of the
    /// `base_k` nearest photons of `base` to p within max_radius (nearest first; all of them
    /// there when fewer), and `base_to_here`, each base photon's id in this map or
    /// PointIndex::removed. It searches only the added photons' small index and answers exactly
    /// as k_nearest does; false (out unspecified) when the removed ones leave the list too short
    /// to tell, and for a map that is not composed.
    bool k_nearest_from_base(Vec3 p, int k, float max_radius, const PhotonMap& base,
                             const std::vector<uint32_t>& base_nearest, int base_k,
                             const std::vector<uint32_t>& base_to_here, std::vector<Neighbour>& out) const;
    /// Every photon within `radius` of `p`, in an order that depends on the map and `p` alone.
    void within(Vec3 p, float radius, std::vector<Neighbour>& out) const;

    /// Irradiance at p (normal n) from photons arriving on n's side: the power of the k - 1
    /// nearest / (pi r^2), r the distance to the k-th photon (or the maximum radius, and every
    /// photon found, when fewer are found). Leaving the k-th out makes it unbiased: for photons
    /// of density d, pi r^2 d follows Gamma(k), whose reciprocal's mean is 1 / (k - 1). The sum
    /// of all k, the textbook form, is too high by k / (k - 1). `radius`, when given, receives
    /// the estimate's radius.
    Rgb estimate_irradiance(Vec3 p, Vec3 n, const DensitySettings& settings, float* radius = nullptr) const;

    /// The same estimate with a cone filter (Jensen 2001, eq. 7.7, k_cone = 1), which keeps sharp
    /// caustic edges sharper: sum of power (1 - d / r) / ((1 - 2/3) pi r^2).
    /// `radius`, when given, receives the estimate's radius.
    Rgb estimate_irradiance_cone(Vec3 p, Vec3 n, const DensitySettings& settings, float* radius = nullptr) const;

    /// The estimate_irradiance of photons on the surface under p, over the share of its disc
    /// that `coverage` finds the surface reaches (held at 1/16 and above, what one probe gives):
    /// photons in cells whose probe missed the surface, or in front of the disc's plane beyond
    /// the probes' lift, count only if the surface reaches them. `radius` receives the estimate's radius,
    /// `probes` the disc's probes.
    Rgb estimate_irradiance_on_surface(Vec3 p, Vec3 n, const DensitySettings& settings, const SurfaceCoverage& coverage,
                                       uint64_t seed, float* radius = nullptr, DiscProbes* probes = nullptr) const;
    /// The same from `nearest`, what k_nearest(p, settings.k, settings.max_radius) gives.
    Rgb irradiance_on_surface(const std::vector<Neighbour>& nearest, Vec3 p, Vec3 n, const DensitySettings& settings,
                              const SurfaceCoverage& coverage, uint64_t seed, float* radius = nullptr,
                              DiscProbes* probes = nullptr) const;

    /// Photons indexed on their own (not composed over another map's index).
    size_t indexed_here() const;

private:
    /// What a composed map adds to its base's index: the ids of base's points and of the added
    /// ones, both in their tree's order (PointIndex::Mapped), and the added points' tree.
    struct Overlay {
        std::vector<uint32_t> base_ids;
        std::vector<uint32_t> added_ids;
        PointIndex added;
    };

    std::vector<Photon> m_photons;
    long m_emitted = 0;
    std::shared_ptr<const PointIndex> m_index;  // shared with the maps composed over this one
    std::shared_ptr<const Overlay> m_overlay;   // null unless composed
};

/// The same photons in the same order, bit for bit (photon.h same_bits); the index aside.
bool same_photons(const PhotonMap& a, const PhotonMap& b);

class IrradiancePhotons;

/// How a frame gets the irradiance values at static photons that something changed around:
/// estimated again by searching its whole map (the photon method, which needs every value, and
/// estimates every frame from scratch), or carried (the localized method): the static value plus
/// the change, the photons removed and added within the static estimate's disc, each with its
/// sign, over that disc's area and share, wherever no dynamic object comes within reach of the
/// disc's probes. A carried value is the fixed-radius estimate over the frame's map on the
/// static disc; it costs what changed in the disc, and a photon far off in the disc changes it
/// by its own power, not by moving the k-th photon. Where a dynamic object does come within
/// reach, the value is estimated again, its neighbours from the static photon's list of a few
/// more (IrradiancePhotons::wider_nearest, kept once found: for the few values a localized frame
/// needs, not the photon method's every value, a list for each being 300 bytes).
enum class ChangedValues { searched, carried };

/// What a frame's irradiance photons take from the segment's static ones instead of estimating
/// again (docs/notes/localized-irradiance-at-photons.md): the value at a photon the frame
/// kept from the static map is the static one where no photon was removed or added within its
/// estimate's radius and no dynamic object lies within its probes' extent. It is then the same,
/// bit for bit: the same neighbours in the same order (ties go by index, and the frame's map keeps
/// the static photons' order), the same disc, probes that meet the same static surfaces. Where
/// photons were removed or added, `changed_values` says what to do.
struct StaticIrradianceReuse {
    const IrradiancePhotons* values = nullptr;  // over the static map, probing the static scene
    KeptStaticPhotons kept;
    ChangedValues changed_values = ChangedValues::searched;
    // The static photons removed, their power negated, then the photons added, each in its map's
    // order, and their index.
    std::vector<Photon> changes;
    PointIndex changed;
    std::vector<BoundingSphere> dynamic;  // the dynamic objects
};

/// The reuse of `values` (over `static_map`) by a frame whose global map is `frame_map`, which
/// keeps `kept` of the static photons.
std::shared_ptr<const StaticIrradianceReuse> make_static_irradiance_reuse(
    const IrradiancePhotons& values, const PhotonMap& static_map, const PhotonMap& frame_map, KeptStaticPhotons kept,
    ChangedValues changed_values, std::vector<BoundingSphere> dynamic);

/// The photons of `frame_map` that are photons of `static_map` bit for bit (same_bits), equal
/// ones taken in order. For a frame traced whole, what its composition from the static paths
/// would have told.
KeptStaticPhotons kept_static_photons_by_bits(const PhotonMap& frame_map, const PhotonMap& static_map);

/// Irradiance precomputed at one in `stride` photons of a global map (Christensen 1999), chosen
/// by a hash of the photon itself, so that a photon a frame keeps from the static map carries a
/// value in both or in neither: the estimate at the photon, which counts itself like any other
/// photon (right for photons of quasi-random paths, which crowd each other less than random
/// points: docs/notes/truth-density-estimate.md), divided by the share of its disc on the surface (`coverage`;
/// none: the whole disc; its probes turned by the same hash). Lazily: each value is computed the
/// first time a look-up needs it, then kept. A frame of the localized method looks up only near
/// its few L_y records, so most values are never needed (compute_all() when they all are), and
/// with `reuse` those nothing changed around are the static ones (about a fifth on BALL: the
/// changed photons are whole path tails, spread over the room), and where something did change,
/// carried or estimated again as `reuse` says (ChangedValues). An estimate made again finds its
/// k nearest photons from the static photon's list of a few more (wider_nearest, kept once
/// found) and the frame's added photons, without searching the whole map, whenever the removed
/// ones leave that list long enough to tell: the same neighbours, the same value. With `reuse`
/// the values' index is the static values' updated (PointIndex::updated), not built. Thread-safe;
/// values do not depend on which thread computes them first. The map must outlive this object
/// and stay where it is, and so must what `coverage` and `reuse` refer to while values are
/// computed.
class IrradiancePhotons {
public:
    IrradiancePhotons(const PhotonMap& global, int stride, const DensitySettings& settings, SurfaceCoverage coverage,
                      std::shared_ptr<const StaticIrradianceReuse> reuse = nullptr);

    /// The irradiance of the nearest precomputed photon whose normal agrees with n, if any
    /// lies within `max_radius`. One further from p than its own estimate's radius, in a cell
    /// of its estimate's disc that the surface did not reach, or in front of p's plane, counts
    /// only if the surface at p reaches it (`coverage`): near a lamp's closed housing against a
    /// wall the nearest is often inside, where the light trapped in the housing is bright.
    std::optional<Rgb> lookup(Vec3 p, Vec3 n, float max_radius) const;
    /// Computes every value now, in parallel: faster than on demand when gathers will cover the
    /// whole scene anyway (the photon method, the static pass), since photons are visited in order.
    void compute_all() const;
    /// Photons that carry a precomputed value, how many values have been estimated so far, and
    /// how many were taken from `reuse` as they are instead.
    size_t size() const { return m_values.size(); }
    long computed() const { return m_computed.load(); }
    long reused() const { return m_reused.load(); }
    /// Of the computed values, those whose neighbours came from the static photons' lists.
    long from_static_lists() const { return m_from_static_lists.load(); }
    /// Values carried: the static value plus the change around it (ChangedValues::carried).
    long carried() const { return m_carried.load(); }

    /// Photons beyond the k nearest that a static photon's list keeps: as many as may be removed
    /// around it in a frame before the list cannot tell the frame's k nearest.
    static constexpr int wider_margin = 16;

    /// An estimate, its disc's radius (max_radius when fewer photons were found) and its probes.
    struct Value {
        Rgb E;
        float radius = 0;
        DiscProbes probes;
    };

private:
    /// Value i, computed the first time.
    const Value& value(uint32_t i) const;
    /// Value i as `m_reuse` has it, as it is or `carried`, if it may be taken from there.
    std::optional<Value> reused_value(uint32_t i, bool& carried) const;
    /// The ids of the k + wider_margin nearest photons to value i's photon (a map of its own),
    /// found the first time.
    const std::vector<uint32_t>& wider_nearest(uint32_t i) const;
    /// The k nearest photons to value i's photon from the static photon's wider_nearest list, if
    /// they tell them.
    bool nearest_from_static(uint32_t i, std::vector<Neighbour>& out) const;

    const PhotonMap* m_global;
    DensitySettings m_settings;
    SurfaceCoverage m_coverage;
    std::shared_ptr<const StaticIrradianceReuse> m_reuse;
    std::vector<uint32_t> m_photon;  // per value: its photon, ascending
    std::vector<uint64_t> m_hash;    // and the photon's hash (the probes' turn)
    std::vector<Vec3> m_n;
    // With `reuse`, per value: the static value its photon carries, or PointIndex::removed.
    std::vector<uint32_t> m_static_carrier;
    mutable std::vector<Value> m_values;
    std::unique_ptr<std::atomic<uint8_t>[]> m_state;        // per value: empty, being written, ready
    mutable std::vector<std::vector<uint32_t>> m_wider;     // per value, without `reuse`: wider_nearest
    std::unique_ptr<std::atomic<uint8_t>[]> m_wider_state;  // and its state, as m_state
    mutable std::atomic<long> m_computed = 0, m_reused = 0, m_from_static_lists = 0, m_carried = 0;
    PointIndex m_index;
    uint64_t m_id = 0;  // unique in the process: whose values a thread's last look-up answered with
};

}  // namespace steadylight
