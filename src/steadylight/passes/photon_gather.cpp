#include "steadylight/passes/photon_gather.h"

#include <algorithm>

#include "steadylight/base/rng.h"
#include "steadylight/shading/surface_point.h"

namespace steadylight {

SurfacePoint face_towards(SurfacePoint sp, Vec3 d) {
    if (dot(sp.ng, d) > 0) {
        sp.ng = -sp.ng;
        sp.ns = -sp.ns;
        sp.nm = -sp.nm;
    }
    return sp;
}

namespace {

/// A final gather at any surface point, seeing everything.
std::function<GatherResult(const SurfacePoint&, Vec3)> make_point_gather(const FrameContext& context,
                                                                         const IrradiancePhotons& photons,
                                                                         float max_radius,
                                                                         const GatherSettings& gather) {
    return
        [&context, &photons, max_radius, gather, dirs = gather_directions(gather, 0)](const SurfacePoint& sp, Vec3 n) {
            return final_gather(sp.p, n, sp.ng, dirs, gather, [&](const Ray& r) {
                return gather_from_photons(context, photons, max_radius, Visibility::everything, r);
            });
        };
}

}  // namespace

GatherHit gather_from_photons(const FrameContext& context, const IrradiancePhotons& photons, float max_radius,
                              Visibility visibility, Ray ray) {
    GatherHit result;
    Rgb beta{1, 1, 1};
    for (int depth = 0; depth < max_gather_chain; ++depth) {
        const std::optional<Hit> hit = context.tracer.intersect(ray, visibility);
        if (!hit) return result;
        if (depth == 0) result.distance = hit->t;
        const SurfacePoint surface = make_surface_point(context.scene, context.frame, ray, *hit);
        beta *= volume_transmittance(context, surface, ray.d, hit->t);  // the segment crossed absorbing glass
        const SurfaceBsdf surface_bsdf = bsdf_at(context, surface);
        const Bsdf* bsdf = &*surface_bsdf;
        std::unique_ptr<Bsdf> coat;
        // Numbers of this ray's own: rays that meet one primitive must not share a choice (with
        // the fixed gather directions, every record on a wall casts rays of the same directions).
        // The same ray gets the same numbers in every frame.
        Pcg32 rng(
            hash_ids(hash_bits(ray.o, ray.d), uint64_t(depth), uint64_t(hit->primitive), uint64_t(surface.object)));
        if (bsdf->is_diffuse()) {
            const SurfacePoint facing = face_towards(surface, ray.d);
            const std::optional<Rgb> E = photons.lookup(surface.p, facing.ng, max_radius);
            const Vec3 wo = OrthonormalBasis::from_normal(facing.nm).to_local(-ray.d);
            if (E) result.L += beta * bsdf->diffuse_reflectance(wo) * *E * inv_pi;
            // Go on along the coat's reflection, kept by Russian roulette (it is a few percent).
            coat = bsdf->non_diffuse_part();
            if (!coat) return result;
            bsdf = coat.get();
        }
        // Follow specular and glossy surfaces along one deterministic sample.
        const float u_lobe = rng.next_float();
        const std::optional<Bounce> bounce =
            sample_bounce(*bsdf, surface, ray.d, rng.next_vec2(), u_lobe, TransportMode::radiance);
        if (!bounce) return result;
        Rgb weight = bounce->sample.weight;
        if (coat) {
            const float survive = std::min(1.0f, max_component(weight));
            if (!(rng.next_float() < survive)) return result;
            weight = weight / survive;
        }
        beta *= weight;
        ray = bounce->ray;
    }
    return result;
}

std::optional<CachePoint> cache_point_at(const FrameContext& context, Visibility visibility, int x, int y,
                                         CentrePath* path) {
    const Camera& camera = context.frame.camera;
    Ray ray = camera.generate_ray(float(x) + 0.5f, float(y) + 0.5f);
    float distance = 0;  // along the path: the pixel's footprint grows with it, mirrors or not
    for (int depth = 0; depth <= max_specular_chain; ++depth) {
        const std::optional<Hit> hit = context.tracer.intersect(ray, visibility);
        if (path) {
            path->bounces = depth;
            if (depth == 0 && hit) path->first_t = hit->t;
        }
        if (!hit) return std::nullopt;
        distance += hit->t;
        const SurfacePoint surface = make_surface_point(context.scene, context.frame, ray, *hit);
        const SurfaceBsdf surface_bsdf = bsdf_at(context, surface);
        const Bsdf& bsdf = *surface_bsdf;
        if (bsdf.is_diffuse()) {
            // The record's normal is the interpolated one, never the normal map's: a normal map
            // would otherwise split the cache into records per bump (docs/materials.md).
            const SurfacePoint sp = face_towards(surface, ray.d);
            return CachePoint{sp.p, sp.ns, sp.ng, camera.pixel_footprint(distance), sp.object};
        }
        // Rough glass is followed as smooth glass of its index would be: the camera's rays through
        // it spread around that path, where the records then are. Other glossy surfaces end it.
        std::unique_ptr<Bsdf> smooth;
        const Bsdf* through = &bsdf;
        if (!bsdf.is_delta()) {
            const MaterialDesc& m =
                context.scene.desc().materials[size_t(context.scene.object(surface.object).material)];
            if (m.type != MaterialType::dielectric) return std::nullopt;
            smooth = make_dielectric(m.ior, m.transmittance);
            through = smooth.get();
        }
        // Through glass along the refracted ray (the likelier branch, unless totally reflected),
        // off mirrors along the reflected one.
        const std::optional<Bounce> bounce =
            sample_bounce(*through, surface, ray.d, {0.5f, 0.5f}, 0.9999f, TransportMode::radiance);
        if (!bounce) return std::nullopt;
        ray = bounce->ray;
    }
    return std::nullopt;
}

CacheBuildStats build_photon_cache(IrradianceCache& cache, const PhotonCacheBuild& build) {
    const Camera& camera = build.context.frame.camera;
    const std::vector<Vec3> fixed_dirs = gather_directions(build.gather, 0);
    return build_cache_over_image(
        cache, camera.width, camera.height,
        [&](int x, int y) -> std::optional<CachePoint> {
            if (build.may_want && !build.may_want(x, y)) return std::nullopt;
            const std::optional<CachePoint> point = cache_point_at(build.context, build.visibility, x, y);
            if (point && build.wanted && !build.wanted(*point, x, y)) return std::nullopt;
            return point;
        },
        [&](const CachePoint& point, uint64_t id) {
            const std::vector<Vec3> dirs =
                build.gather.fixed_directions ? fixed_dirs : gather_directions(build.gather, id);
            return final_gather(point.p, point.n, point.ng, dirs, build.gather, [&](const Ray& r) {
                return gather_from_photons(build.context, build.photons, build.max_radius, build.visibility, r);
            });
        });
}

PointFallbacks make_point_fallbacks(const FrameContext& context, const IrradiancePhotons& photons, float max_radius,
                                    const GatherSettings& gather) {
    GatherSettings rough = gather;
    rough.theta_strata = std::max(2, gather.theta_strata / 4);
    rough.phi_strata = std::max(4, gather.phi_strata / 4);
    return {make_point_gather(context, photons, max_radius, gather),
            make_point_gather(context, photons, max_radius, rough),
            [&photons, max_radius](const SurfacePoint& sp, Vec3) {
                GatherResult result;
                result.record.E = photons.lookup(sp.p, sp.ng, max_radius).value_or(Rgb{});
                return result;
            }};
}

GreyImage record_picture(const Camera& camera, const std::vector<IrradianceRecord>& records) {
    GreyImage picture(camera.width, camera.height);
    for (const IrradianceRecord& record : records) {
        const std::optional<Vec2> film = camera.project(record.p);
        if (!film || film->x < 0 || film->y < 0 || film->x >= float(camera.width) || film->y >= float(camera.height))
            continue;
        picture.at(int(film->x), int(film->y)) = 1;
    }
    return picture;
}

std::optional<Rgb> interpolated_irradiance(const IrradianceCache& cache, Vec3 p, Vec3 n,
                                           std::vector<uint32_t>* used_ids) {
    if (const std::optional<Rgb> E = cache.interpolate(p, n, 1, used_ids)) return E;
    // Between records after neighbour clamping, or inside a pixel off its centre: let the
    // records reach twice as far.
    return cache.interpolate(p, n, 2, used_ids);
}

Rgb cached_irradiance(const IrradianceCache& cache, const SurfacePoint& sp, Vec3 n,
                      const std::function<GatherResult(const SurfacePoint&, Vec3)>& gather,
                      std::atomic<long>& fallbacks, std::atomic<long>& gather_rays, std::vector<uint32_t>* used_ids) {
    if (const std::optional<Rgb> E = interpolated_irradiance(cache, sp.p, n, used_ids)) return *E;
    // Not covered (a point seen only through a mirror): gather here without keeping the record.
    const GatherResult g = gather(sp, n);
    ++fallbacks;
    gather_rays += g.rays;
    return g.record.E;
}

}  // namespace steadylight
