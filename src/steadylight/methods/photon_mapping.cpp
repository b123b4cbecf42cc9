// The photon method: the passes of one frame from scratch (photon_mapping.h).
#include "steadylight/methods/photon_mapping.h"

#include "steadylight/passes/frame_photons.h"
#include "steadylight/passes/photon_gather.h"
#include "steadylight/passes/shading_pass.h"

namespace steadylight {

PhotonFrame render_photon_mapped(const FrameContext& context, const PhotonMappingSettings& settings,
                                 const StaticPhotonPaths* paths) {
    const Stopwatch total;
    PhotonFrame out;
    FrameStats& stats = out.stats;
    stats.frame = context.frame.frame;

    // Pass 1: photons.
    const FramePhotons traced(context, settings, stats, paths, paths ? paths->irradiance.get() : nullptr);
    const IrradiancePhotons& irradiance_photons = traced.irradiance;

    // Pass 2a: irradiance precomputed at a share of the global photons, then the irradiance
    // cache over the image by final gathering.
    IrradianceCache cache(settings.cache);
    const float max_radius = settings.irradiance_estimate.max_radius;
    const CacheBuildStats built = timed_phase("irradiance cache", stats.cache_s, [&] {
        irradiance_photons.compute_all();  // the gathers over the whole image need nearly all
        return build_photon_cache(
            cache, {context, irradiance_photons, max_radius, settings.gather, Visibility::everything, {}});
    });
    stats.irradiance_records = built.records_added;

    // Pass 2b: shade every pixel.
    const PointFallbacks fallback = make_point_fallbacks(context, irradiance_photons, max_radius, settings.gather);
    std::atomic<long> fallbacks = 0, gather_rays = 0;
    const auto indirect = [&](const SurfacePoint& sp, Vec3 n, const PixelSample& pixel, ExtraLayers*) {
        return remembered(pixel.memo, pixel.reach, sp, n, [&] {
            return PixelMemo::Values{cached_irradiance(cache, sp, n, fallback.at(pixel.share), fallbacks, gather_rays)};
        })[0];
    };
    ShadedFrame shaded = timed_phase("shading", stats.shading_s, [&] {
        return shade_frame(context, settings.shading, traced.maps.caustic, indirect, [&](const Ray& ray) {
            return gather_from_photons(context, irradiance_photons, max_radius, Visibility::everything, ray).L;
        });
    });
    stats.caustics_s = shaded.caustic_cpu_s;
    stats.fallback_gathers = fallbacks;
    stats.gather_rays = built.gather_rays + gather_rays;

    take_common_layers(shaded, out);
    out.records = record_picture(context.frame.camera, cache.records());
    stats.irradiance_photons = irradiance_photons.computed();
    stats.irradiance_reused = irradiance_photons.reused();
    stats.irradiance_from_lists = irradiance_photons.from_static_lists();
    stats.total_s = total.elapsed_s();
    return out;
}

}  // namespace steadylight
