#include "steadylight/methods/path_tracer.h"

#include <atomic>

#include "steadylight/base/checkpoint.h"
#include "steadylight/base/parallel.h"
#include "steadylight/base/sampling.h"
#include "steadylight/base/settings_check.h"
#include "steadylight/shading/surface_point.h"

namespace steadylight {
namespace {

constexpr int tile_size = 16;

/// Direct light from one sampled light, weighted against BSDF sampling by MIS.
Rgb estimate_direct(const FrameContext& context, const SurfacePoint& sp, const Frame& frame,
                    const Bsdf& bsdf, Vec3 wo, Pcg32& rng) {
    const float u_select = rng.next_float();
    const std::optional<LightSample> light = context.lights.sample(sp.p, u_select, rng.next_vec2());
    if (!light) return {};
    const Vec3 wi = frame.to_local(light->wi);
    const Rgb f = bsdf.eval(wo, wi);
    if (is_black(f)) return {};
    if (context.tracer.occluded(spawn_ray_to(sp.p, sp.ng, light->p))) return {};
    const float weight = light->is_delta ? 1.0f : power_heuristic(light->pdf, bsdf.pdf(wo, wi));
    return f * light->Li * (std::abs(wi.z) * weight / light->pdf);
}

}  // namespace

Rgb trace_path(const FrameContext& context, Ray ray, Pcg32& rng, const PathTracerSettings& settings) {
    Rgb L, beta{1, 1, 1};
    bool specular_bounce = true;  // the camera ray counts emitters fully, like a delta bounce
    float bsdf_pdf = 0;
    Vec3 previous_p;
    for (int depth = 0; depth <= settings.max_depth; ++depth) {
        const std::optional<Hit> hit = context.tracer.intersect(ray);
        if (!hit) break;  // the background is black
        const SurfacePoint sp = make_surface_point(context.scene, context.frame, ray, *hit);
        const Rgb emission = context.frame.emission[size_t(sp.object)];

        // Add emitted light (as bright as it is at this frame), weighted against light sampling
        // at the previous vertex.
        if (!is_black(emission)) {
            const Rgb Le = emitted_radiance(context.scene.object(sp.object), emission, sp.ng, -ray.d);
            if (specular_bounce) {
                L += beta * Le;
            } else {
                const float light_pdf = context.lights.pdf_emitter(sp.object, previous_p, sp.p, sp.ng);
                L += beta * Le * power_heuristic(bsdf_pdf, light_pdf);
            }
        }
        if (depth == settings.max_depth) break;

        // Sample direct light, then continue the path by sampling the BSDF.
        const Bsdf& bsdf = context.bsdf_of(sp.object);
        const Frame frame = Frame::from_normal(sp.ns);
        const Vec3 wo = frame.to_local(-ray.d);
        if (!bsdf.is_delta()) L += beta * estimate_direct(context, sp, frame, bsdf, wo, rng);
        const float u_lobe = rng.next_float();
        const std::optional<BsdfSample> bs = bsdf.sample(wo, rng.next_vec2(), u_lobe, TransportMode::radiance);
        if (!bs) break;
        beta *= bs->weight;
        if (is_black(beta)) break;
        specular_bounce = bs->is_delta;
        bsdf_pdf = bs->pdf;
        previous_p = sp.p;
        ray = spawn_ray(sp.p, sp.ng, frame.to_world(bs->wi));

        // Russian roulette: end low-throughput paths, reweighting the survivors.
        if (depth + 1 >= settings.roulette_start_depth) {
            const float survive = std::min(1.0f, max_component(beta));
            if (rng.next_float() >= survive) break;
            beta = beta / survive;
        }
    }
    return L;
}

Image render_path_traced(const FrameContext& context, const PathTracerSettings& settings,
                         const TileProgress& progress) {
    begin_phase("path tracing");
    const Camera& camera = context.frame.camera;
    Image image(camera.width, camera.height);
    const int tiles = ((camera.width + tile_size - 1) / tile_size) * ((camera.height + tile_size - 1) / tile_size);
    std::atomic<int> tiles_done = 0;
    parallel_for_tiles(camera.width, camera.height, tile_size, [&](int x0, int y0, int x1, int y1) {
        for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
                Pcg32 rng(hash_ids(uint64_t(context.frame.frame), uint64_t(y) * uint64_t(camera.width) + uint64_t(x),
                                   settings.seed));
                Rgb sum;
                const Vec2 shift = rng.next_vec2();
                for (int s = 0; s < settings.samples_per_pixel; ++s) {
                    const Vec2 jitter = stratified_2d(uint32_t(s), uint32_t(settings.samples_per_pixel), shift);
                    const Rgb L = trace_path(context, camera.generate_ray(float(x) + jitter.x, float(y) + jitter.y),
                                             rng, settings);
                    // A NaN or infinity from a degenerate path is dropped, not smeared over the frame.
                    if (is_finite(L)) sum += L;
                }
                image.at(x, y) = sum / float(settings.samples_per_pixel);
            }
        }
        if (progress) progress(++tiles_done, tiles);
    });
    return image;
}

void validate(const PathTracerSettings& settings, const std::string& where) {
    check_setting_range(where + "/samples_per_pixel", settings.samples_per_pixel, 1, 1 << 20);
    check_setting_range(where + "/max_depth", settings.max_depth, 0, 10000);
    check_setting_range(where + "/roulette_start_depth", settings.roulette_start_depth, 0, 10000);
}

}  // namespace steadylight
