#include "steadylight/integrators/photon_mapping.h"

#include <atomic>

#include "steadylight/base/parallel.h"
#include "steadylight/base/rng.h"
#include "steadylight/base/sampling.h"
#include "steadylight/shading/surface_point.h"

namespace steadylight {
namespace {

constexpr int tile_size = 16;

/// The lighting at a pixel split the way the EXR's layers are.
struct Components {
    Rgb direct, indirect, caustic, specular;
    Rgb sum() const { return direct + indirect + caustic + specular; }
};

/// Which of a pixel's light samples a camera ray takes: sample k of this ray is number
/// first + k of `count`, stratified over the pixel (base/sampling.h stratified_2d), so the
/// shadow rays of all the pixel's camera rays together cover the lights evenly.
struct LightStrata {
    uint32_t first = 0;
    uint32_t count = 0;  // 0: no stratification, independent samples
    Vec2 shift;
};

/// Everything the shading pass reads, built by the phases before it.
struct Shader {
    const FrameContext& context;
    const PhotonMappingSettings& settings;
    const TracedPhotons& photons;
    const IrradiancePhotons& irradiance_photons;
    const IrradianceCache& cache;
    const std::vector<Vec3>& gather_dirs;
    std::atomic<long>& fallback_gathers;
    std::atomic<long>& gather_rays;
    std::atomic<long>& caustic_ns;  // time in caustic estimates, summed over threads

    Components shade(const Ray& ray, int depth, bool count_emission, const LightStrata& strata, Pcg32& rng) const;
    Rgb direct_light(const SurfacePoint& sp, const Frame& frame, const Bsdf& bsdf, Vec3 wo, const LightStrata& strata,
                     Pcg32& rng) const;
    Rgb indirect_irradiance(const SurfacePoint& sp, Vec3 n) const;
    GatherHit gather_radiance(Ray ray) const;
};

/// The side of the surface a ray arrives on: normals facing the viewer.
SurfacePoint face_towards(SurfacePoint sp, Vec3 d) {
    if (dot(sp.ng, d) > 0) {
        sp.ng = -sp.ng;
        sp.ns = -sp.ns;
    }
    return sp;
}

/// Radiance a final-gather ray brings back: at a diffuse surface rho / pi times the precomputed
/// irradiance there (its whole outgoing radiance, direct light included, DESIGN.md §1); through
/// mirrors and glass it continues; emitters add nothing (that light is L_d).
GatherHit Shader::gather_radiance(Ray ray) const {
    GatherHit result;
    Rgb beta{1, 1, 1};
    for (int depth = 0; depth < 4; ++depth) {
        const std::optional<Hit> hit = context.tracer.intersect(ray);
        if (!hit) return result;
        if (depth == 0) result.distance = hit->t;
        const SurfacePoint sp = face_towards(make_surface_point(context.scene, context.frame, ray, *hit), ray.d);
        const Bsdf& bsdf = context.bsdf_of(sp.object);
        if (bsdf.is_diffuse()) {
            const std::optional<Rgb> E = irradiance_photons.lookup(sp.p, sp.ng, settings.irradiance_estimate.max_radius);
            if (E) result.L = beta * bsdf.diffuse_reflectance() * *E * inv_pi;
            return result;
        }
        // Follow specular and glossy surfaces along one deterministic sample.
        const Frame frame = Frame::from_normal(sp.ns);
        Pcg32 rng(hash_ids(uint64_t(hit->primitive), uint64_t(depth), uint64_t(sp.object)));
        const float u_lobe = rng.next_float();
        const std::optional<BsdfSample> bs = bsdf.sample(frame.to_local(-ray.d), rng.next_vec2(), u_lobe, TransportMode::radiance);
        if (!bs) return result;
        beta *= bs->weight;
        ray = spawn_ray(sp.p, sp.ng, frame.to_world(bs->wi));
    }
    return result;
}

Rgb Shader::indirect_irradiance(const SurfacePoint& sp, Vec3 n) const {
    if (const std::optional<Rgb> E = cache.interpolate(sp.p, n)) return *E;
    // Between records after neighbour clamping, or inside a pixel off its centre: let the
    // records reach twice as far before gathering anew.
    if (const std::optional<Rgb> E = cache.interpolate(sp.p, n, 2)) return *E;
    // Not covered (a point seen only through a mirror): gather here without keeping the record,
    // so the cache stays independent of shading order.
    const GatherResult g = final_gather(sp.p, n, sp.ng, gather_dirs, settings.gather,
                                        [&](const Ray& r) { return gather_radiance(r); });
    ++fallback_gathers;
    gather_rays += g.rays;
    return g.record.E;
}

Rgb Shader::direct_light(const SurfacePoint& sp, const Frame& frame, const Bsdf& bsdf, Vec3 wo,
                          const LightStrata& strata, Pcg32& rng) const {
    Rgb sum;
    for (int s = 0; s < settings.direct_samples; ++s) {
        const float u_select = rng.next_float();
        const Vec2 u = strata.count ? stratified_2d(strata.first + uint32_t(s), strata.count, strata.shift) : rng.next_vec2();
        const std::optional<LightSample> light = context.lights.sample(sp.p, u_select, u);
        if (!light) continue;
        const Vec3 wi = frame.to_local(light->wi);
        const Rgb f = bsdf.eval(wo, wi);
        if (is_black(f) || context.tracer.occluded(spawn_ray_to(sp.p, sp.ng, light->p))) continue;
        sum += f * light->Li * (std::abs(wi.z) / light->pdf);
    }
    return sum / float(settings.direct_samples);
}

Components Shader::shade(const Ray& ray, int depth, bool count_emission, const LightStrata& strata, Pcg32& rng) const {
    Components c;
    const std::optional<Hit> hit = context.tracer.intersect(ray);
    if (!hit) return c;
    const SurfacePoint surface = make_surface_point(context.scene, context.frame, ray, *hit);
    const ObjectDesc& object = context.scene.object(surface.object);
    // An emitter seen by the camera is direct light; seen through a mirror the caller files it
    // under specular.
    if (count_emission && object.is_emitter()) c.direct += emitted_radiance(object, surface.ng, -ray.d);
    const SurfacePoint sp = face_towards(surface, ray.d);
    const Bsdf& bsdf = context.bsdf_of(sp.object);
    const Frame frame = Frame::from_normal(sp.ns);
    const Vec3 wo = frame.to_local(-ray.d);
    if (bsdf.is_diffuse()) {
        const Rgb albedo_over_pi = bsdf.diffuse_reflectance() * inv_pi;
        c.direct += direct_light(sp, frame, bsdf, wo, strata, rng);
        c.indirect = albedo_over_pi * indirect_irradiance(sp, sp.ns);
        const Stopwatch caustic_time;
        c.caustic = albedo_over_pi * photons.caustic.estimate_irradiance_cone(sp.p, sp.ng, settings.caustic_estimate);
        caustic_ns += long(caustic_time.elapsed_s() * 1e9);
        return c;
    }
    // Glossy surfaces take direct light by light sampling; the sampled bounce then carries only
    // indirect light (emission is not counted twice). Mirrors and glass see emitters directly.
    if (!bsdf.is_delta()) c.direct += direct_light(sp, frame, bsdf, wo, strata, rng);
    if (depth >= settings.max_specular_depth) return c;
    const float u_lobe = rng.next_float();
    const std::optional<BsdfSample> bs = bsdf.sample(wo, rng.next_vec2(), u_lobe, TransportMode::radiance);
    if (!bs) return c;
    const Ray next = spawn_ray(sp.p, sp.ng, frame.to_world(bs->wi));
    c.specular = bs->weight * shade(next, depth + 1, bs->is_delta, LightStrata{}, rng).sum();
    return c;
}

/// The surface point a pixel's centre sees directly, where its indirect light is cached.
std::optional<CachePoint> cache_point_at(const FrameContext& context, int x, int y) {
    const Camera& camera = context.frame.camera;
    const Ray ray = camera.generate_ray(float(x) + 0.5f, float(y) + 0.5f);
    const std::optional<Hit> hit = context.tracer.intersect(ray);
    if (!hit || !context.bsdf_of(hit->object).is_diffuse()) return std::nullopt;
    const SurfacePoint sp = face_towards(make_surface_point(context.scene, context.frame, ray, *hit), ray.d);
    return CachePoint{sp.p, sp.ns, sp.ng, camera.pixel_footprint(hit->t)};
}

Image record_picture(const Camera& camera, const IrradianceCache& cache) {
    Image picture(camera.width, camera.height);
    for (const IrradianceRecord& record : cache.records()) {
        const std::optional<Vec2> film = camera.project(record.p);
        if (!film || film->x < 0 || film->y < 0 || film->x >= float(camera.width) || film->y >= float(camera.height)) continue;
        picture.at(int(film->x), int(film->y)) = {1, 1, 1};
    }
    return picture;
}

}  // namespace

PhotonFrame render_photon_mapped(const FrameContext& context, const PhotonMappingSettings& settings) {
    const Stopwatch total;
    PhotonFrame out;
    FrameStats& stats = out.stats;
    stats.method = "photon";
    stats.frame = context.frame.frame;

    // Pass 1: photons, and irradiance precomputed at a share of the global ones.
    Stopwatch phase;
    const TracedPhotons photons = trace_photons(context, settings.photons);
    const IrradiancePhotons irradiance_photons(photons.global, settings.irradiance_stride, settings.irradiance_estimate);
    stats.photon_tracing_s = phase.elapsed_s();
    stats.global_photons_emitted = photons.global.emitted();
    stats.global_photons_stored = long(photons.global.size());
    stats.caustic_photons_emitted = photons.caustic.emitted();
    stats.caustic_photons_stored = long(photons.caustic.size());
    stats.irradiance_photons = long(irradiance_photons.size());

    // Pass 2a: the irradiance cache over the image, by final gathering.
    phase = Stopwatch();
    const std::vector<Vec3> gather_dirs = gather_directions(settings.gather, 0);
    IrradianceCache cache(settings.cache);
    std::atomic<long> fallback_gathers = 0, gather_rays = 0, caustic_ns = 0;
    const Shader shader{context,    settings,         photons,     irradiance_photons, cache,
                        gather_dirs, fallback_gathers, gather_rays, caustic_ns};
    const Camera& camera = context.frame.camera;
    const CacheBuildStats built = build_cache_over_image(
        cache, camera.width, camera.height, [&](int x, int y) { return cache_point_at(context, x, y); },
        [&](const CachePoint& point, uint64_t id) {
            const std::vector<Vec3> dirs = settings.gather.fixed_directions ? gather_dirs : gather_directions(settings.gather, id);
            return final_gather(point.p, point.n, point.ng, dirs, settings.gather,
                                [&](const Ray& r) { return shader.gather_radiance(r); });
        });
    stats.cache_s = phase.elapsed_s();
    stats.irradiance_records = built.records_added;

    // Pass 2b: shade every pixel.
    phase = Stopwatch();
    for (Image* image : {&out.beauty, &out.direct, &out.indirect, &out.caustic, &out.specular})
        *image = Image(camera.width, camera.height);
    const int n = settings.samples_per_pixel;
    parallel_for_tiles(camera.width, camera.height, tile_size, [&](int x0, int y0, int x1, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                Pcg32 rng(hash_ids(uint64_t(context.frame.frame), uint64_t(y) * uint64_t(camera.width) + uint64_t(x), 0x9e01));
                Components sum;
                const Vec2 shift = rng.next_vec2();
                const LightStrata strata{0, uint32_t(n * settings.direct_samples), rng.next_vec2()};
                for (int s = 0; s < n; ++s) {
                    const Vec2 jitter = stratified_2d(uint32_t(s), uint32_t(n), shift);
                    const Ray ray = camera.generate_ray(float(x) + jitter.x, float(y) + jitter.y);
                    const Components c = shader.shade(ray, 0, true, {uint32_t(s * settings.direct_samples), strata.count, strata.shift}, rng);
                    if (!is_finite(c.sum())) continue;
                    sum.direct += c.direct, sum.indirect += c.indirect, sum.caustic += c.caustic, sum.specular += c.specular;
                }
                out.direct.at(x, y) = sum.direct / float(n);
                out.indirect.at(x, y) = sum.indirect / float(n);
                out.caustic.at(x, y) = sum.caustic / float(n);
                out.specular.at(x, y) = sum.specular / float(n);
                out.beauty.at(x, y) = sum.sum() / float(n);
            }
    });
    stats.direct_s = phase.elapsed_s();
    stats.caustics_s = double(caustic_ns) * 1e-9;
    stats.fallback_gathers = fallback_gathers;
    stats.gather_rays = built.gather_rays + gather_rays;
    out.records = record_picture(camera, cache);
    stats.total_s = total.elapsed_s();
    return out;
}

}  // namespace steadylight
