#include "steadylight/methods/path_tracer.h"

#include <atomic>

#include "steadylight/base/checkpoint.h"
#include "steadylight/base/parallel.h"
#include "steadylight/base/sampling.h"
#include "steadylight/base/settings_check.h"
#include "steadylight/base/stopwatch.h"
#include "steadylight/shading/surface_point.h"

namespace steadylight {
namespace {

constexpr int tile_size = 16;

// Fixed-seed streams hash this where the default streams hash the frame number, which stays
// far below it: the two kinds of stream are seeded from different words.
constexpr uint64_t fixed_seed_streams = uint64_t(1) << 63;

/// The random streams of one pixel. By default one stream, seeded from (frame, pixel), draws the
/// pixel's stratification shift and then the numbers of every camera sample in turn. With
/// `fixed_seed` the shift and each camera sample have a stream of their own, seeded from (pixel,
/// sample) and not from the frame: a path that meets a moving object changes its own sample's
/// numbers only, and every other sample of the pixel repeats the previous frame's path exactly.
class PixelStreams {
public:
    PixelStreams(const PathTracerSettings& settings, int frame, uint64_t pixel)
        : m_fixed(settings.fixed_seed),
          m_pixel(pixel),
          m_seed(settings.seed),
          m_rng(m_fixed ? hash_ids(fixed_seed_streams, pixel, m_seed) : hash_ids(uint64_t(frame), pixel, m_seed)) {}

    /// The stream of the pixel's stratification shift, drawn before any sample.
    Pcg32& shift() { return m_rng; }
    /// The stream of camera sample `sample`; call it for the samples in order 0, 1, ...
    Pcg32& sample(int sample) {
        if (m_fixed) m_rng = Pcg32(hash_ids(fixed_seed_streams, m_pixel, m_seed, uint64_t(sample) + 1));
        return m_rng;
    }

private:
    bool m_fixed;
    uint64_t m_pixel, m_seed;
    Pcg32 m_rng;
};

/// Direct light from one sampled light, weighted against BSDF sampling by MIS.
Rgb estimate_direct(const FrameContext& context, const SurfacePoint& sp, const OrthonormalBasis& basis,
                    const Bsdf& bsdf, Vec3 wo, Pcg32& rng, PathCounts& counts) {
    const float u_select = rng.next_float();
    const std::optional<LightSample> light = context.lights.sample(sp.p, u_select, rng.next_vec2(), sp.nm);
    if (!light) return {};
    const Vec3 wi = basis.to_local(light->wi);
    const Rgb f = bsdf.eval(wo, wi);
    if (is_black(f)) return {};
    ++counts.rays;
    if (context.tracer.occluded(shadow_ray(*light, sp.p, sp.ng))) return {};
    const float weight = light->is_delta ? 1.0f : power_heuristic(light->pdf, bsdf.pdf(wo, wi));
    return f * light->Li * (std::abs(wi.z) * weight / light->pdf);
}

/// A pixel's mean radiance over its camera samples, and the share of them that met a surface.
struct PixelEstimate {
    Rgb L;
    float covered = 0;
};

/// Pixel (x, y) over its stratified camera samples.
PixelEstimate estimate_pixel(const FrameContext& context, const PathTracerSettings& settings, int x, int y,
                             PathCounts& counts) {
    const Camera& camera = context.frame.camera;
    PixelStreams streams(settings, context.frame.frame, uint64_t(y) * uint64_t(camera.width) + uint64_t(x));
    Rgb sum;
    int met_surface = 0;
    const Vec2 shift = streams.shift().next_vec2();
    for (int s = 0; s < settings.samples_per_pixel; ++s) {
        const Vec2 jitter = stratified_2d(uint32_t(s), uint32_t(settings.samples_per_pixel), shift);
        const Ray ray = camera.generate_ray(float(x) + jitter.x, float(y) + jitter.y);
        const PathRadiance path = trace_path(context, ray, streams.sample(s), settings, counts);
        met_surface += path.met_surface;
        // A NaN or infinity from a degenerate path is dropped, not smeared over the frame.
        if (is_finite(path.L)) sum += path.L;
    }
    return {sum / float(settings.samples_per_pixel), float(met_surface) / float(settings.samples_per_pixel)};
}

}  // namespace

PathRadiance trace_path(const FrameContext& context, Ray ray, Pcg32& rng, const PathTracerSettings& settings,
                        PathCounts& counts) {
    Rgb L, beta{1, 1, 1};
    bool met_surface = false;
    bool specular_bounce = true;  // the camera ray counts emitters fully, like a delta bounce
    float bsdf_pdf = 0;
    Vec3 previous_p, previous_n;  // the last surface point's, for MIS weights
    for (int depth = 0; depth <= settings.max_depth; ++depth) {
        ++counts.rays;
        const std::optional<Hit> hit = context.tracer.intersect(ray);
        if (!hit) {
            if (depth == 0 && context.frame.camera.transparent_background) break;
            // The lights from far away, weighted against sampling them at the previous vertex.
            L += beta * (specular_bounce ? context.lights.escaped_radiance(ray.d)
                                         : context.lights.escaped_radiance(previous_p, ray.d, previous_n, bsdf_pdf));
            break;
        }
        ++counts.vertices;
        met_surface = true;
        const SurfacePoint sp = make_surface_point(context.scene, context.frame, ray, *hit);
        beta *= volume_transmittance(context, sp, ray.d, hit->t);  // the segment crossed absorbing glass
        const Rgb emission = context.frame.emission[size_t(sp.object)];

        // Add emitted light (as bright as it is at this frame), weighted against light sampling
        // at the previous vertex.
        if (!is_black(emission)) {
            const Rgb Le = emitted_radiance_at(context, sp, -ray.d);
            if (specular_bounce) {
                L += beta * Le;
            } else {
                const float light_pdf = context.lights.pdf_emitter(sp.object, previous_p, sp.p, sp.ng);
                L += beta * Le * power_heuristic(bsdf_pdf, light_pdf);
            }
        }
        if (depth == settings.max_depth) break;

        // Sample direct light, then continue the path by sampling the BSDF.
        const SurfaceBsdf surface_bsdf = bsdf_at(context, sp);
        const Bsdf& bsdf = *surface_bsdf;
        const OrthonormalBasis basis = OrthonormalBasis::from_normal(sp.nm);
        const Vec3 wo = basis.to_local(-ray.d);
        if (!bsdf.is_delta()) L += beta * estimate_direct(context, sp, basis, bsdf, wo, rng, counts);
        const float u_lobe = rng.next_float();
        const std::optional<BsdfSample> bs = bsdf.sample(wo, rng.next_vec2(), u_lobe, TransportMode::radiance);
        if (!bs) break;
        beta *= bs->weight;
        if (is_black(beta)) break;
        specular_bounce = bs->is_delta;
        bsdf_pdf = bs->pdf;
        previous_p = sp.p;
        previous_n = sp.nm;
        ray = spawn_ray(sp.p, sp.ng, basis.to_world(bs->wi));

        // Russian roulette: end low-throughput paths, reweighting the survivors.
        if (depth + 1 >= settings.roulette_start_depth) {
            const float survive = std::min(1.0f, max_component(beta));
            if (rng.next_float() >= survive) break;
            beta = beta / survive;
        }
    }
    return {L, met_surface};
}

PathFrame render_path_traced(const FrameContext& context, const PathTracerSettings& settings,
                             const TileProgress& progress) {
    const Stopwatch total;
    begin_phase("path tracing");
    const Camera& camera = context.frame.camera;
    PathFrame out{Image(camera.width, camera.height), std::nullopt, {}};
    if (camera.transparent_background) out.alpha = Image(camera.width, camera.height);
    const int tiles = ((camera.width + tile_size - 1) / tile_size) * ((camera.height + tile_size - 1) / tile_size);
    std::atomic<int> tiles_done = 0;
    // Each tile counts on its own and adds its counts once: integer sums do not depend on the
    // order the tiles finish in.
    std::atomic<long> rays = 0, vertices = 0;
    parallel_for_tiles(camera.width, camera.height, tile_size, [&](int x0, int y0, int x1, int y1) {
        PathCounts counts;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                const PixelEstimate pixel = estimate_pixel(context, settings, x, y, counts);
                out.beauty.at(x, y) = pixel.L;
                if (out.alpha) out.alpha->at(x, y) = Rgb{1, 1, 1} * pixel.covered;
            }
        rays += counts.rays;
        vertices += counts.vertices;
        if (progress) progress(++tiles_done, tiles);
    });
    FrameStats& stats = out.stats;
    stats.frame = context.frame.frame;
    stats.camera_samples = long(camera.width) * long(camera.height) * long(settings.samples_per_pixel);
    stats.path_rays = rays;
    stats.path_vertices = vertices;
    stats.total_s = total.elapsed_s();
    return out;
}

void validate(const PathTracerSettings& settings, const std::string& where) {
    check_setting_range(where + "/samples_per_pixel", settings.samples_per_pixel, 1, 1 << 20);
    check_setting_range(where + "/max_depth", settings.max_depth, 0, 10000);
    check_setting_range(where + "/roulette_start_depth", settings.roulette_start_depth, 0, 10000);
}

}  // namespace steadylight
