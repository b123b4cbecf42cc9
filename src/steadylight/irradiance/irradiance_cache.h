// The irradiance cache (Ward, Rubinstein & Clear 1988): records of gathered irradiance kept in a
// spatial index (a hierarchical hash grid over the records' spheres of validity) and interpolated with Ward's
// weights w_i = 1 / (|p - p_i| / R_i + sqrt(1 - n . n_i)) plus the gradient terms (Ward &
// Heckbert 1992). Radii are clamped against neighbours (Krivanek et al. 2006, "Making radiance
// and irradiance caching practical"). Reads are thread-safe; inserts are not (the builder inserts
// between parallel phases, in a fixed order, so results never depend on thread count).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "steadylight/irradiance/irradiance_record.h"

namespace steadylight {

struct CacheSettings {
    float accuracy = 0.25f;        // Ward's a: a record is used where w_i > 1 / a
    float min_spacing_px = 2.0f;   // a record reaches (a * R) at least this many pixels...
    float max_spacing_px = 32.0f;  // ...and at most this many
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(CacheSettings, accuracy, min_spacing_px, max_spacing_px)
void validate(const CacheSettings& settings, const std::string& where);

class IrradianceCache {
public:
    explicit IrradianceCache(CacheSettings settings = {});
    ~IrradianceCache();
    IrradianceCache(IrradianceCache&&) noexcept;
    IrradianceCache& operator=(IrradianceCache&&) noexcept;

    /// Adds a record; its radius must already be clamped (see clamp_radius). Not on a cache
    /// made by with_irradiance (nor on the one it was made from).
    void insert(const IrradianceRecord& record);

    /// This cache's records with other irradiance: `records` are this cache's, in order, with
    /// their E (and nothing that places them: p, n, radius) changed. The two share the index,
    /// as L_t's correction of the static cache does every frame, without indexing it again.
    IrradianceCache with_irradiance(std::vector<IrradianceRecord> records) const;

    /// \brief Irradiance at `p` with unit normal `n`, interpolated from the records whose weight
    /// exceeds 1 / accuracy, with gradient extrapolation. std::nullopt when no record qualifies.
    /// `reach_scale` in [1, 2] lets records reach further (1 / (accuracy * reach_scale)), for a
    /// second try before gathering anew. `used_ids`, when given, gets the ids of the records it
    /// used (usable_ids), empty with std::nullopt.
    std::optional<Rgb> interpolate(Vec3 p, Vec3 n, float reach_scale = 1,
                                   std::vector<uint32_t>* used_ids = nullptr) const;

    /// The records interpolate(p, n, reach_scale) uses, by id in ascending order (empty: none).
    void usable_ids(Vec3 p, Vec3 n, float reach_scale, std::vector<uint32_t>& out) const;
    /// interpolate(p, n, reach_scale) from the records it uses, `ids` (usable_ids of this cache or
    /// of one whose records lie where these do, as with_irradiance keeps them): the same bits,
    /// without searching the index. `ids` must not be empty.
    Rgb interpolate_over(std::span<const uint32_t> ids, Vec3 p, Vec3 n) const;

    /// True when some record would be used at (p, n): no new gather is needed there.
    bool covers(Vec3 p, Vec3 n) const;

    /// Neighbour clamping (Krivanek 2006): R_i = min(R_i, R_j + |p_i - p_j|) over records j whose
    /// spheres overlap i's. Call after a batch of inserts; deterministic for a given record order.
    void clamp_radii_to_neighbours();

    const std::vector<IrradianceRecord>& records() const;
    const CacheSettings& settings() const;

private:
    struct Index;
    IrradianceCache(CacheSettings settings, std::shared_ptr<Index> index);
    /// Keeps what a look-up needs of record i beside it (m_gradient_scales).
    void set_derived(size_t i);

    CacheSettings m_settings;
    std::vector<IrradianceRecord> m_records;
    std::vector<std::array<float, 3>> m_gradient_scales;  // per record: gradient_scales()
    std::shared_ptr<Index> m_index;
};

/// The validity radius from a gather: the harmonic mean distance clamped to
/// [min_spacing_px, max_spacing_px] / accuracy times `pixel_footprint` (world size of one pixel
/// at p), so that a record's reach a * R spans that many pixels.
float clamp_radius(float harmonic_mean_distance, float pixel_footprint, const CacheSettings& settings);

}  // namespace steadylight
