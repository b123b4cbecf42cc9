// The localized method's frame pass (frame_pass.h).
#include "steadylight/passes/frame_pass.h"

#include <algorithm>

#include <spdlog/spdlog.h>

#include "steadylight/base/check.h"
#include "steadylight/base/parallel.h"
#include "steadylight/passes/frame_photons.h"
#include "steadylight/passes/influence.h"
#include "steadylight/passes/photon_gather.h"
#include "steadylight/passes/pixel_reuse.h"
#include "steadylight/passes/record_correction.h"
#include "steadylight/photons/surface_coverage.h"

namespace steadylight {
namespace {

/// Marks the pixels whose caustic estimates may read photons that changed: on the screen, the
/// estimates' reach about each (every pixel when the map changed whole).
std::vector<uint8_t> caustic_changes(const Camera& camera, const FramePhotons::CausticChanges& changes,
                                     const DensitySettings& estimate) {
    std::vector<uint8_t> mask(size_t(camera.width) * size_t(camera.height), changes.everywhere ? 1 : 0);
    if (!changes.everywhere) {
        std::vector<BoundingSphere> reach;
        for (const Vec3 p : changes.points) reach.push_back({p, estimate.max_radius * 1.001f});
        mark_spheres_on_screen(camera, reach, mask);
    }
    return mask;
}

/// Marks the pixels whose indirect light a frame may change against the static frame: on the
/// screen, the reach of every corrected record that changed (the furthest any interpolation
/// reads it: IrradianceCache::interpolate at twice its reach), and where the influence blends
/// in L_y.
std::vector<uint8_t> indirect_changes(const Camera& camera, const IrradianceCache& static_cache,
                                      const std::vector<uint8_t>& changed_records, const InfluenceMap& influence,
                                      const LocalizedSettings& localized) {
    std::vector<uint8_t> mask(size_t(camera.width) * size_t(camera.height), 0);
    const float reach_per_radius = 2 * static_cache.settings().accuracy * 1.001f;
    std::vector<BoundingSphere> reach;
    for (size_t i = 0; i < changed_records.size(); ++i)
        if (changed_records[i]) {
            const IrradianceRecord& r = static_cache.records()[i];
            reach.push_back({r.p, r.radius * reach_per_radius});
        }
    mark_spheres_on_screen(camera, reach, mask);  // FrameChanges::records
    if (!influence.values.empty())
        parallel_for_chunks(camera.height, 16, [&](long begin, long end) {
            for (int y = int(begin); y < int(end); ++y)
                for (int x = 0; x < camera.width; ++x)
                    if (blend_weight(influence.at(x, y), localized) > 0)
                        mask[size_t(y) * size_t(camera.width) + size_t(x)] |= FrameChanges::blend;
        });
    return mask;
}

/// The shading pass's slots for the layers of this method's own (shading_pass.h ExtraLayers).
enum ExtraSlot { influence_slot, dynamic_slot, L_y_slot, L_t_slot, indirect_static_slot, slot_count };
static_assert(slot_count <= max_extra_layers);

/// The influence layer's largest value, 1000 x tau_upper: L_y alone long before.
constexpr float max_influence_shown = 1000;

/// The `changed` layer: per pixel the ChangedTerm bits of the terms a frame redid (pixel_reuse.h).
GreyImage changed_picture(const Camera& camera, const std::vector<uint8_t>& changed) {
    GreyImage image = GreyImage::unfilled(camera.width, camera.height);
    std::copy(changed.begin(), changed.end(), image.pixels.begin());
    return image;
}

/// What a camera ray found at its diffuse point, for the layers.
struct IndirectParts {
    float influence;
    Rgb L_y, L_t;  // irradiance
    bool on_dynamic;
    std::optional<Rgb> E_static;  // the static cache's, interpolated (interpolated_irradiance)
};

/// The localized method's own layers: influence, L_y, L_t (as radiance) and the static cache's
/// indirect light. The last is taken on one camera ray per pixel only (it is smooth), and
/// weighted so that the pixel's average comes out right.
void fill_layers(const FrameContext& context, const SurfacePoint& sp, const PixelSample& pixel,
                 const IndirectParts& parts, ExtraLayers& extra) {
    // The layers show the base's albedo as seen head-on: the shading pass's own wo is not here.
    const Rgb albedo_over_pi = bsdf_at(context, sp)->diffuse_reflectance({0, 0, 1}) * inv_pi;
    // Dynamic objects always take L_y: shown as the largest influence, and in their own mask.
    // The influence is infinite where there is no static indirect light; every layer stays
    // finite (a compositor's blur would spread an inf), and far below the half-float range.
    extra[influence_slot] =
        Rgb{1, 1, 1} * (parts.on_dynamic ? max_influence_shown : std::min(parts.influence, max_influence_shown));
    extra[dynamic_slot] = Rgb{1, 1, 1} * (parts.on_dynamic ? 1.0f : 0.0f);
    extra[L_y_slot] = albedo_over_pi * parts.L_y;
    extra[L_t_slot] = albedo_over_pi * parts.L_t;
    if (parts.E_static) extra[indirect_static_slot] = albedo_over_pi * *parts.E_static * float(pixel.samples);
}

/// What the localized method's shading reads at diffuse points.
struct LocalizedLighting {
    const IrradianceCache& static_cache;     // for the layer of the static cache's indirect light
    const IrradianceCache& dynamic_cache;    // L_y
    const IrradianceCache& corrected_cache;  // L_t
    const InfluenceMap& influence;           // no values: L_t everywhere off the dynamic objects
    const IrradiancePhotons& irradiance;
    const PhotonMap& caustic;
    bool frozen = false;
    /// L_t's records are the static cache's as they are (the static frame, the frozen baseline):
    /// L_t interpolated is the static cache's indirect light.
    bool corrected_is_static = false;
};

/// The influence at pixel (x, y); 0 where the frame has no influence map (frozen, static frame).
float influence_at(const LocalizedLighting& lighting, int x, int y) {
    return lighting.influence.values.empty() ? 0.0f : lighting.influence.at(x, y);
}

/// What a frame that reuses a static frame's pixels computes for them anew: a reused pixel's
/// influence layer (when the analysis layers are made), and the indirect light of a pixel whose
/// corrected records changed.
void set_reused_values(PixelReuse& reuse, const LocalizedLighting& lighting, AnalysisLayers analysis) {
    // A reused pixel's influence layer: what its camera rays that reached a diffuse point would
    // have written (fill_layers), summed in the same order.
    if (analysis == AnalysisLayers::made)
        reuse.reused_layers = [&lighting](int x, int y, const PixelTrace& trace, PixelSums& sums) {
            Rgb sum;
            for (int ray = 0; ray < trace.surface_rays; ++ray)
                sum += Rgb{1, 1, 1} * std::min(influence_at(lighting, x, y), max_influence_shown);
            sums.extra[influence_slot] = sum;
        };
    // A pixel whose corrected records changed, and nothing else: L_t interpolated again at each of
    // its look-ups over the records it interpolated in the static frame (the corrected records
    // are the static ones, moved nowhere: the same records, the same weights), then each camera
    // ray's share summed in ray order, as shading sums it (L_i is L_t there, the blend weight
    // being 0, and its L_t layer the same product).
    reuse.look_up_again = [&reuse, &lighting](int, int, size_t pixel, PixelSums& sums) {
        const StaticFrame& base = reuse.base();
        const KeptLookUps look_ups = base.look_ups(pixel);
        std::array<std::optional<Rgb>, PixelMemo::capacity> L_t;
        const auto L_t_at = [&](int i) -> const Rgb& {
            std::optional<Rgb>& E = L_t[size_t(i)];
            if (!E) {
                thread_local std::vector<uint32_t> ids;
                look_ups.records(i, ids);
                E = lighting.corrected_cache.interpolate_over(ids, look_ups.point(i), look_ups.normal(i));
            }
            return *E;
        };
        Rgb L_i;
        if (look_ups.same_rays()) {
            // Every ray's share is the same product, added as many times: the same sum.
            if (const int i = look_ups.look_up(0); i != KeptLookUps::none) {
                const Rgb share = look_ups.albedo(0) * L_t_at(i);
                for (int ray = 0; ray < base.samples; ++ray) L_i += share;
            }
        } else {
            for (int ray = 0; ray < base.samples; ++ray)
                if (const int i = look_ups.look_up(ray); i != KeptLookUps::none)
                    L_i += look_ups.albedo(ray) * L_t_at(i);
        }
        sums.indirect = sums.extra[L_t_slot] = L_i;
    };
}

/// The shading pass of the localized method: L_i = f(g(I)) L_y + (1 - f(g(I))) L_t, and L_y on
/// dynamic objects; the frame's own, or the static frame's (visibility static_only).
ShadedFrame shade_localized(const FrameContext& context, const LocalizedLighting& lighting,
                            const PhotonMappingSettings& photon, const LocalizedSettings& localized,
                            Visibility visibility, AnalysisLayers analysis, PixelSource* source, FrameStats& stats) {
    const float max_radius = photon.irradiance_estimate.max_radius;
    const PointFallbacks fallback = make_point_fallbacks(context, lighting.irradiance, max_radius, photon.gather);
    std::atomic<long> fallbacks = 0, gather_rays = 0;
    const auto interpolate_or_gather = [&](const IrradianceCache& cache, const SurfacePoint& sp, Vec3 n,
                                           const PixelSample& pixel, std::vector<uint32_t>* used_ids = nullptr,
                                           bool* gathered_here = nullptr) {
        std::atomic<long> gathered = 0, rays = 0;
        const Rgb E = cached_irradiance(cache, sp, n, fallback.at(pixel.share), gathered, rays, used_ids);
        if (gathered && pixel.recorder) pixel.recorder->add_flags(pixel.pixel_index, PixelRecorder::gather);
        if (gathered_here) *gathered_here = gathered > 0;
        fallbacks += gathered, gather_rays += rays;
        return E;
    };
    const auto indirect = [&](const SurfacePoint& sp, Vec3 n, const PixelSample& pixel, ExtraLayers* extra) {
        const bool on_dynamic = context.scene.object(sp.object).is_dynamic();
        const float I = on_dynamic ? 0.0f : influence_at(lighting, pixel.x, pixel.y);
        const float weight = on_dynamic ? 1.0f : (lighting.frozen ? 0.0f : blend_weight(I, localized));
        // A recorder that keeps look-ups is told which corrected records L_t was interpolated from.
        thread_local std::vector<uint32_t> L_t_ids;
        const bool tell_ids = pixel.recorder && weight < 1;
        bool looked_up = false, L_t_gathered = false;
        const auto [L_y, L_t, unused] = remembered(pixel.memo, pixel.reach, sp, n, [&] {
            looked_up = true;
            return PixelMemo::Values{weight > 0 ? interpolate_or_gather(lighting.dynamic_cache, sp, n, pixel) : Rgb{},
                                     weight < 1 ? interpolate_or_gather(lighting.corrected_cache, sp, n, pixel,
                                                                        tell_ids ? &L_t_ids : nullptr, &L_t_gathered)
                                                : Rgb{},
                                     Rgb{}};
        });
        if (tell_ids && looked_up && pixel.memo && pixel.memo->last_used() >= 0)
            pixel.recorder->add_look_up_records(pixel.pixel_index, pixel.memo->last_used(), L_t_ids);
        if (extra) {
            // The static cache's indirect light, on the pixel's first camera ray: L_t itself where
            // that ray just interpolated it from the static records.
            std::optional<Rgb> E_static;
            if (pixel.sample == 0 && !on_dynamic)
                E_static = lighting.corrected_is_static && looked_up && weight < 1
                               ? (L_t_gathered ? std::nullopt : std::optional<Rgb>(L_t))
                               : interpolated_irradiance(lighting.static_cache, sp.p, n);
            fill_layers(context, sp, pixel, {I, L_y, L_t, on_dynamic, E_static}, *extra);
        }
        return L_y * weight + L_t * (1 - weight);
    };
    ShadedFrame shaded = shade_frame(
        context, photon.shading, lighting.caustic, indirect,
        [&](const Ray& ray) {
            return gather_from_photons(context, lighting.irradiance, max_radius, visibility, ray).L;
        },
        visibility, source, analysis == AnalysisLayers::made ? slot_count : 0,
        1u << influence_slot | 1u << dynamic_slot);
    stats.fallback_gathers += fallbacks;
    stats.gather_rays += gather_rays;
    return shaded;
}

}  // namespace

std::optional<StaticFrame> make_static_frame(const FrameContext& context, const StaticSolution& solution,
                                             const PhotonMappingSettings& photon, const LocalizedSettings& localized,
                                             double max_bytes, AnalysisLayers analysis) {
    SL_CHECK(solution.photon_paths);
    const StaticPhotonPaths& paths = *solution.photon_paths;
    SL_CHECK(paths.irradiance);
    const IrradiancePhotons& irradiance = *paths.irradiance;
    // Built as every frame builds L_t, so that its interpolations are the frame's bit for bit.
    const IrradianceCache corrected_cache =
        correct_static_cache(solution.cache, PhotonMap{}, localized.correction, nullptr);
    const IrradianceCache no_dynamic_cache(photon.cache);
    const InfluenceMap no_influence;
    StaticFrame out;
    StaticFrameMaker maker(out, context.frame, photon.shading.samples_per_pixel, corrected_cache, max_bytes);
    FrameStats stats;
    shade_localized(context,
                    {solution.cache, no_dynamic_cache, corrected_cache, no_influence, irradiance, paths.caustic.photons,
                     false, true},
                    photon, localized, Visibility::static_only, analysis, &maker, stats);
    if (!maker.fits()) return std::nullopt;
    maker.finish_frame();
    return out;
}

namespace {

/// The static frame a frame may reuse pixels of: the solution's, when its view and lights are
/// the frame's (never for the frozen baseline); else null.
const StaticFrame* reusable_static_frame(const FrameContext& context, const StaticSolution& solution, bool frozen) {
    const StaticFrame* base = solution.static_frame.get();
    return base && !frozen && same_view_and_lights(context.scene, context.frame, base->made_at) ? base : nullptr;
}

/// L_y: the dynamic cache, built only where the influence is felt and on dynamic objects.
/// `kept`, in a still view: what its pixel centres see with the dynamic objects left out, and
/// `near_dynamic` where a centre's ray may meet a dynamic object (pixels_near_dynamic).
CacheBuildStats build_dynamic_cache(IrradianceCache& dynamic_cache, const FrameContext& context,
                                    const IrradiancePhotons& irradiance, const InfluenceMap& influence,
                                    const PhotonMappingSettings& photon, const LocalizedSettings& localized,
                                    bool frozen, const KeptCentreRays* kept, const std::vector<uint8_t>& near_dynamic) {
    const auto felt = [&](int x, int y) { return !frozen && influence.at(x, y) > localized.tau_lower; };
    const auto wanted = [&](const CachePoint& point, int x, int y) {
        return context.scene.object(point.object).is_dynamic() || felt(x, y);
    };
    // Where the influence is not felt, only a centre that sees a dynamic object wants a record.
    std::function<bool(int, int)> may_want;
    if (kept)
        may_want = [&](int x, int y) { return felt(x, y) || !kept->sees_static_directly(context, x, y, near_dynamic); };
    return build_photon_cache(dynamic_cache, {context, irradiance, photon.irradiance_estimate.max_radius, photon.gather,
                                              Visibility::everything, wanted, may_want});
}

/// Which pixels a frame shades again against the static frame `base`, and what it reuses
/// (pixel_reuse.h), given `near_dynamic` (pixels_near_dynamic); the counts go into `stats`.
PixelPlan plan_frame_pixels(const FrameContext& context, const StaticFrame& base, std::vector<uint8_t> near_dynamic,
                            const FramePhotons& traced, const IrradianceCache& static_cache,
                            const std::vector<uint8_t>& changed_records, const InfluenceMap& influence,
                            const PhotonMappingSettings& photon, const LocalizedSettings& localized,
                            FrameStats& stats) {
    const Camera& camera = context.frame.camera;
    const FrameChanges changes{context.tracer.dynamic_bounds(),
                               std::move(near_dynamic),
                               context.lights.bounds(),
                               indirect_changes(camera, static_cache, changed_records, influence, localized),
                               std::find(changed_records.begin(), changed_records.end(), 1) != changed_records.end(),
                               traced.caustic_changes.everywhere || !traced.caustic_changes.points.empty(),
                               caustic_changes(camera, traced.caustic_changes, photon.shading.caustic_estimate),
                               changed_records};
    PixelPlan plan = plan_pixels(camera, base, changes);
    stats.pixels_reused = plan.reused, stats.pixels_looked_up_again = plan.looked_up_again;
    stats.pixels_direct_again = plan.direct_again;
    stats.pixels_redone_but_direct = plan.redone_but_direct, stats.pixels_redone = plan.redone;
    std::copy(std::begin(plan.changed_pixels), std::end(plan.changed_pixels), stats.pixels_changed.begin());
    return plan;
}

/// Moves the shaded layers into the frame and adds the pictures of the records and of what was
/// redone (`changed`: empty when the frame shaded every term of every pixel), when asked for.
void take_localized_layers(ShadedFrame& shaded, const Camera& camera, const IrradianceCache& static_cache,
                           const IrradianceCache& dynamic_cache, std::vector<uint8_t> changed, AnalysisLayers analysis,
                           LocalizedFrame& out) {
    take_common_layers(shaded, out);
    if (analysis == AnalysisLayers::left_out) return;
    out.influence = std::move(shaded.grey_extra[influence_slot]);
    out.dynamic = std::move(shaded.grey_extra[dynamic_slot]);
    out.L_y = std::move(shaded.extra[L_y_slot]);
    out.L_t = std::move(shaded.extra[L_t_slot]);
    out.indirect_static = std::move(shaded.extra[indirect_static_slot]);
    out.static_records = record_picture(camera, static_cache.records());
    out.dynamic_records = record_picture(camera, dynamic_cache.records());
    if (changed.empty()) changed.assign(size_t(camera.width) * size_t(camera.height), 15);
    out.changed = changed_picture(camera, changed);
}

}  // namespace

std::shared_ptr<const StaticFrame> segment_static_frame(const Scene& scene, RayTracer& tracer, const Segment& segment,
                                                        const StaticSolution& solution,
                                                        const PhotonMappingSettings& photon,
                                                        const LocalizedSettings& localized, double available_bytes,
                                                        AnalysisLayers analysis) {
    if (distinct_views(scene, segment).size() != 1) {
        spdlog::info("pixel reuse: off for frames {}-{}: the camera moves", segment.first, segment.last);
        return nullptr;
    }
    // A frame reuses the static frame's pixels only where its lights are the static frame's (and
    // never beside an emitter that moves).
    const FrameState first = scene.evaluate(segment.first);
    const bool emitter_moves = std::any_of(scene.dynamic_objects().begin(), scene.dynamic_objects().end(),
                                           [&](int object) { return scene.object(object).is_moving_light(); });
    for (int frame = segment.first + 1; frame <= segment.last; ++frame)
        if (emitter_moves || !scene.evaluate(frame).same_lights(first)) {
            spdlog::info("pixel reuse: off for frames {}-{}: lights move", segment.first, segment.last);
            return nullptr;
        }
    const Camera& camera = scene.evaluate(segment.first).camera;
    const double pixels = double(camera.width) * double(camera.height);
    const double max_bytes = static_frame_memory_share * available_bytes;
    const auto off = [&](double bytes, const char* what) {
        spdlog::info(
            "pixel reuse: off: the static frame would need {} {:.0f} MB, more than {:.0f}% of the {:.0f} MB "
            "available; every pixel is shaded in every frame",
            what, bytes / 1e6, static_frame_memory_share * 100, available_bytes / 1e6);
        return nullptr;
    };
    const double least = pixels * double(StaticFrame::fixed_bytes_per_pixel());
    if (least > max_bytes) return off(least, "at least");
    const Stopwatch time;
    const Bsdfs bsdfs = make_bsdfs(scene);
    const PlacedFrame view(scene, tracer, bsdfs, segment.first);
    std::optional<StaticFrame> made =
        make_static_frame(view.context(), solution, photon, localized, max_bytes, analysis);
    if (!made) return off(max_bytes, "more than");
    const double bytes = double(made->bytes());
    spdlog::info("static frame: {}x{} pixels, {:.1f} MB ({:.0f} bytes a pixel), shaded in {:.2f} s", camera.width,
                 camera.height, bytes / 1e6, bytes / pixels, time.elapsed_s());
    return std::make_shared<const StaticFrame>(std::move(*made));
}

LocalizedFrame run_frame_pass(const FrameContext& context, const StaticSolution& solution,
                              const PhotonMappingSettings& photon, const LocalizedSettings& localized,
                              StaticCacheUse use, AnalysisLayers analysis) {
    const Stopwatch total;
    const bool frozen = use == StaticCacheUse::frozen;
    LocalizedFrame out;
    FrameStats& stats = out.stats;
    stats.frame = context.frame.frame;
    stats.static_records = solution.records();
    const IrradianceCache& static_cache = solution.cache;

    // Photons in the complete scene: the global, caustic and dynamic maps.
    const StaticPhotonPaths* paths = solution.photon_paths.get();
    const FramePhotons traced(context, photon, stats, paths, paths ? paths->irradiance.get() : nullptr,
                              ChangedValues::carried, solution.compose_photons);
    const TracedPhotons& photons = traced.maps;

    // In a still view, what the pixel centres see where nothing dynamic is in the way is the
    // segment's (the influence and L_y ask for it).
    const StaticFrame* base = reusable_static_frame(context, solution, frozen);
    const KeptCentreRays* centre_rays = base ? solution.centre_rays.get() : nullptr;
    // And the pixels whose camera rays may meet a dynamic object (L_y's placement and the plan ask).
    std::vector<uint8_t> near_dynamic =
        base ? pixels_near_dynamic(context.frame.camera, context.tracer.dynamic_bounds()) : std::vector<uint8_t>{};

    // Influence of the dynamic objects on each pixel's point.
    const InfluenceMap influence = timed_phase("influence", stats.influence_s, [&] {
        if (centre_rays)
            centre_rays->make(context, static_cache, influence_step(localized, context.frame.camera.height));
        return frozen ? InfluenceMap{}
                      : estimate_influence(context, photons.dynamic, static_cache, localized,
                                           photon.irradiance_estimate.max_radius, centre_rays);
    });

    // L_y: the dynamic cache.
    IrradianceCache dynamic_cache(photon.cache);
    const CacheBuildStats built = timed_phase("L_y", stats.cache_s, [&] {
        return build_dynamic_cache(dynamic_cache, context, traced.irradiance, influence, photon, localized, frozen,
                                   centre_rays, near_dynamic);
    });
    stats.irradiance_records = built.records_added;
    stats.gather_rays = built.gather_rays;

    // L_t: the static records corrected by the dynamic map (the frozen baseline: as they are).
    std::vector<uint8_t> changed_records;
    const IrradianceCache own_corrected_cache = timed_phase("L_t", stats.correction_s, [&] {
        if (frozen) return IrradianceCache(photon.cache);
        solution.correction_points->make(context, static_cache, localized.correction);
        return correct_static_cache(static_cache, photons.dynamic, localized.correction,
                                    solution.correction_points.get(), &changed_records);
    });
    const IrradianceCache& corrected_cache = frozen ? static_cache : own_corrected_cache;

    // Shade: L_i = f(g(I)) L_y + (1 - f(g(I))) L_t, and L_y on dynamic objects; with a static
    // frame only the pixels the frame's changes reach (planning them is part of the phase).
    const LocalizedLighting lighting{static_cache,      dynamic_cache,   corrected_cache, influence,
                                     traced.irradiance, photons.caustic, frozen,          frozen};
    PixelPlan plan;
    ShadedFrame shaded = timed_phase("shading", stats.shading_s, [&] {
        if (!base)
            return shade_localized(context, lighting, photon, localized, Visibility::everything, analysis, nullptr,
                                   stats);
        plan = plan_frame_pixels(context, *base, std::move(near_dynamic), traced, static_cache, changed_records,
                                 influence, photon, localized, stats);
        PixelReuse reuse(*base, plan);
        set_reused_values(reuse, lighting, analysis);
        const Camera& camera = context.frame.camera;
        solution.kept_direct_light->make(
            camera.width, camera.height, photon.shading.samples_per_pixel, photon.shading.direct_samples,
            KeptDirectLight::max_bytes_per_pixel * double(camera.width) * double(camera.height));
        reuse.keep_direct_light(*solution.kept_direct_light, context.tracer);
        ShadedFrame reused =
            shade_localized(context, lighting, photon, localized, Visibility::everything, analysis, &reuse, stats);
        stats.pixels_direct_from_kept = reuse.direct_from_kept();
        return reused;
    });
    stats.caustics_s = shaded.caustic_cpu_s;

    take_localized_layers(shaded, context.frame.camera, static_cache, dynamic_cache, std::move(plan.changed), analysis,
                          out);
    stats.irradiance_photons = traced.irradiance.computed();
    stats.irradiance_reused = traced.irradiance.reused();
    stats.irradiance_from_lists = traced.irradiance.from_static_lists();
    stats.irradiance_carried = traced.irradiance.carried();
    stats.total_s = total.elapsed_s();
    return out;
}

}  // namespace steadylight
