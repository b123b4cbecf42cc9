// The localized method's frame pass (frame_pass.h).
#include "steadylight/passes/frame_pass.h"

#include <algorithm>

#include "steadylight/base/parallel.h"
#include "steadylight/passes/frame_photons.h"
#include "steadylight/passes/influence.h"
#include "steadylight/passes/photon_gather.h"

namespace steadylight {
namespace {

/// The static records with the dynamic map's irradiance estimate added at each (paper §3.3, L_t).
IrradianceCache corrected_cache(const IrradianceCache& static_cache, const PhotonMap& dynamic, const DensitySettings& density) {
    std::vector<IrradianceRecord> records = static_cache.records();
    parallel_for_chunks(long(records.size()), 64, [&](long begin, long end) {
        for (long i = begin; i < end; ++i) {
            IrradianceRecord& r = records[size_t(i)];
            const Rgb delta = dynamic.estimate_irradiance(r.p, r.n, density);
            r.E = {std::max(0.0f, r.E.r + delta.r), std::max(0.0f, r.E.g + delta.g), std::max(0.0f, r.E.b + delta.b)};
        }
    });
    IrradianceCache corrected(static_cache.settings());
    for (const IrradianceRecord& r : records) corrected.insert(r);
    return corrected;
}

/// The shading pass's slots for the layers of this method's own (shading_pass.h ExtraLayers).
enum ExtraSlot { influence_slot, dynamic_slot, L_y_slot, L_t_slot, indirect_static_slot, slot_count };
static_assert(slot_count <= max_extra_layers);

/// What a camera ray found at its diffuse point, for the layers.
struct IndirectParts {
    float influence;
    Rgb L_y, L_t;  // irradiance
    bool on_dynamic;
};

/// The localized method's own layers: influence, L_y, L_t (as radiance) and the static cache's
/// indirect light. The last is looked up on one camera ray per pixel only (it is smooth), and
/// weighted so that the pixel's average comes out right.
void fill_layers(const FrameContext& context, const IrradianceCache& static_cache, const SurfacePoint& sp, Vec3 n,
                 const PixelSample& pixel, const IndirectParts& parts, ExtraLayers& extra) {
    // The layers show the base's albedo as seen head-on: the shading pass's own wo is not here.
    const Rgb albedo_over_pi = bsdf_at(context, sp)->diffuse_reflectance({0, 0, 1}) * inv_pi;
    // Dynamic objects always take L_y: shown as the largest influence, and in their own mask.
    // The influence is infinite where there is no static indirect light; every layer stays
    // finite (a compositor's blur would spread an inf), and far below the half-float range.
    constexpr float max_influence_shown = 1000;  // 1000 x tau_upper: L_y alone long before
    extra[influence_slot] = Rgb{1, 1, 1} * (parts.on_dynamic ? max_influence_shown : std::min(parts.influence, max_influence_shown));
    extra[dynamic_slot] = Rgb{1, 1, 1} * (parts.on_dynamic ? 1.0f : 0.0f);
    extra[L_y_slot] = albedo_over_pi * parts.L_y;
    extra[L_t_slot] = albedo_over_pi * parts.L_t;
    if (pixel.sample == 0 && !parts.on_dynamic)
        if (const std::optional<Rgb> E = static_cache.interpolate(sp.p, n, 2))
            extra[indirect_static_slot] = albedo_over_pi * *E * float(pixel.samples);
}

}  // namespace

LocalizedFrame run_frame_pass(const FrameContext& context, const StaticSolution& solution,
                              const PhotonMappingSettings& photon, const LocalizedSettings& localized,
                              StaticCacheUse use) {
    const Stopwatch total;
    const bool frozen = use == StaticCacheUse::frozen;
    LocalizedFrame out;
    FrameStats& stats = out.stats;
    stats.frame = context.frame.frame;
    stats.static_records = solution.records();
    const float max_radius = photon.irradiance_estimate.max_radius;

    // Photons in the complete scene: the global, caustic and dynamic maps.
    const FramePhotons traced(context, photon, stats, solution.photon_paths.get());
    const TracedPhotons& photons = traced.maps;
    const IrradiancePhotons& irradiance = traced.irradiance;

    // Influence of the dynamic objects on each pixel's point.
    const InfluenceMap influence = timed_phase("influence", stats.influence_s, [&] {
        return frozen ? InfluenceMap{} : estimate_influence(context, photons.dynamic, solution.cache, localized, max_radius);
    });

    // L_y: the dynamic cache, only where the influence is felt and on dynamic objects.
    IrradianceCache dynamic_cache(photon.cache);
    const auto wanted = [&](const CachePoint& point, int x, int y) {
        return context.scene.object(point.object).is_dynamic() || (!frozen && influence.at(x, y) > localized.tau_lower);
    };
    const CacheBuildStats built = timed_phase("L_y", stats.cache_s, [&] {
        return build_photon_cache(dynamic_cache, {context, irradiance, max_radius, photon.gather, Visibility::everything, wanted});
    });
    stats.irradiance_records = built.records_added;

    // L_t: the static records corrected by the dynamic map.
    const IrradianceCache& static_cache = solution.cache;
    const IrradianceCache corrected = timed_phase("L_t", stats.correction_s, [&] {
        return frozen ? IrradianceCache(photon.cache)
                      : corrected_cache(static_cache, photons.dynamic, localized.correction_estimate);
    });
    const IrradianceCache& transported = frozen ? static_cache : corrected;

    // Shade: L_i = f(g(I)) L_y + (1 - f(g(I))) L_t, and L_y on dynamic objects.
    const auto full_gather = make_point_gather(context, irradiance, max_radius, photon.gather);
    const auto rough_gather = make_point_gather(context, irradiance, max_radius, rough_gather_settings(photon.gather));
    std::atomic<long> fallbacks = 0, gather_rays = 0;
    const auto indirect = [&](const SurfacePoint& sp, Vec3 n, const PixelSample& pixel, ExtraLayers* extra) {
        const bool on_dynamic = context.scene.object(sp.object).is_dynamic();
        const float I = on_dynamic || influence.values.empty() ? 0.0f : influence.at(pixel.x, pixel.y);
        const float weight = on_dynamic ? 1.0f : (frozen ? 0.0f : blend_weight(I, localized));
        const auto& gather = pixel.minor_branch ? rough_gather : full_gather;
        const auto [L_y, L_t, unused] = remembered(pixel.memo, pixel.reach, sp, n, [&] {
            return PixelMemo::Values{
                weight > 0 ? cached_irradiance(dynamic_cache, sp, n, gather, fallbacks, gather_rays) : Rgb{},
                weight < 1 ? cached_irradiance(transported, sp, n, gather, fallbacks, gather_rays) : Rgb{}, Rgb{}};
        });
        if (extra) fill_layers(context, static_cache, sp, n, pixel, {I, L_y, L_t, on_dynamic}, *extra);
        return L_y * weight + L_t * (1 - weight);
    };
    ShadedFrame shaded = timed_phase("shading", stats.direct_s, [&] {
        return shade_frame(context, photon.shading, photons.caustic, indirect, [&](const Ray& ray) {
            return gather_from_photons(context, irradiance, max_radius, Visibility::everything, ray).L;
        });
    });
    stats.caustics_s = shaded.caustic_cpu_s;
    stats.fallback_gathers = fallbacks;
    stats.gather_rays = built.gather_rays + gather_rays;

    take_common_layers(shaded, out);
    out.influence = std::move(shaded.extra[influence_slot]);
    out.dynamic = std::move(shaded.extra[dynamic_slot]);
    out.L_y = std::move(shaded.extra[L_y_slot]);
    out.L_t = std::move(shaded.extra[L_t_slot]);
    out.indirect_static = std::move(shaded.extra[indirect_static_slot]);
    out.static_records = record_picture(context.frame.camera, static_cache.records());
    out.dynamic_records = record_picture(context.frame.camera, dynamic_cache.records());
    stats.irradiance_photons = irradiance.computed();
    stats.total_s = total.elapsed_s();
    return out;
}

}  // namespace steadylight
