#include "steadylight/integrators/photon_mapping.h"

#include "steadylight/base/checkpoint.h"
#include "steadylight/integrators/photon_gather.h"

namespace steadylight {

Rgb cached_irradiance(const IrradianceCache& cache, const SurfacePoint& sp, Vec3 n,
                      const std::function<GatherResult(const SurfacePoint&, Vec3)>& gather, std::atomic<long>& fallbacks,
                      std::atomic<long>& gather_rays) {
    if (const std::optional<Rgb> E = cache.interpolate(sp.p, n)) return *E;
    // Between records after neighbour clamping, or inside a pixel off its centre: let the
    // records reach twice as far before gathering anew.
    if (const std::optional<Rgb> E = cache.interpolate(sp.p, n, 2)) return *E;
    // Not covered (a point seen only through a mirror): gather here without keeping the record.
    const GatherResult g = gather(sp, n);
    ++fallbacks;
    gather_rays += g.rays;
    return g.record.E;
}

namespace {

/// The photon pass as a phase of the frame: traced, timed and counted in `stats`.
TracedPhotons trace_counted_photons(const FrameContext& context, const PhotonMappingSettings& settings, FrameStats& stats) {
    begin_phase("photons");
    const Stopwatch time;
    TracedPhotons maps = trace_photons(context, settings.photons);
    stats.photon_tracing_s = time.elapsed_s();
    stats.global_photons_emitted = maps.global.emitted();
    stats.global_photons_stored = long(maps.global.size());
    stats.caustic_photons_emitted = maps.caustic.emitted();
    stats.caustic_photons_stored = long(maps.caustic.size());
    stats.dynamic_photons_stored = long(maps.dynamic.size());
    return maps;
}

}  // namespace

FramePhotons::FramePhotons(const FrameContext& context, const PhotonMappingSettings& settings, FrameStats& stats)
    : maps(trace_counted_photons(context, settings, stats)),
      irradiance(maps.global, settings.irradiance_stride, settings.irradiance_estimate) {}

PhotonFrame render_photon_mapped(const FrameContext& context, const PhotonMappingSettings& settings) {
    const Stopwatch total;
    PhotonFrame out;
    FrameStats& stats = out.stats;
    stats.method = "photon";
    stats.frame = context.frame.frame;

    // Pass 1: photons.
    const FramePhotons traced(context, settings, stats);
    const TracedPhotons& photons = traced.maps;
    const IrradiancePhotons& irradiance_photons = traced.irradiance;

    // Pass 2a: irradiance precomputed at a share of the global photons, then the irradiance
    // cache over the image by final gathering.
    begin_phase("irradiance cache");
    Stopwatch phase;
    irradiance_photons.compute_all();  // the gathers over the whole image need nearly all
    IrradianceCache cache(settings.cache);
    const float max_radius = settings.irradiance_estimate.max_radius;
    const CacheBuildStats built = build_photon_cache(
        cache, {context, irradiance_photons, max_radius, settings.gather, Visibility::everything, {}});
    stats.cache_s = phase.elapsed_s();
    stats.irradiance_records = built.records_added;

    // Pass 2b: shade every pixel.
    begin_phase("shading");
    phase = Stopwatch();
    const auto gather = make_point_gather(context, irradiance_photons, max_radius, settings.gather);
    std::atomic<long> fallbacks = 0, gather_rays = 0;
    ShadedFrame shaded = shade_frame(context, settings.shading, photons.caustic, [&](const SurfacePoint& sp, Vec3 n, const PixelSample& pixel, ExtraLayers*) {
        return remembered(pixel.memo, pixel.reach, sp, n, [&] { return PixelMemo::Values{cached_irradiance(cache, sp, n, gather, fallbacks, gather_rays)}; })[0];
    });
    stats.direct_s = phase.elapsed_s();
    stats.caustics_s = shaded.caustic_cpu_s;
    stats.fallback_gathers = fallbacks;
    stats.gather_rays = built.gather_rays + gather_rays;

    take_common_layers(shaded, out);
    out.records = record_picture(context.frame.camera, cache.records());
    stats.irradiance_photons = irradiance_photons.computed();
    stats.total_s = total.elapsed_s();
    return out;
}

}  // namespace steadylight
