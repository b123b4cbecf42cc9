#include "steadylight/photons/distant_photon_share.h"

#include <algorithm>
#include <vector>

#include "steadylight/base/parallel.h"
#include "steadylight/base/rng.h"
#include "steadylight/base/sampling.h"
#include "steadylight/photons/photon_tracer.h"
#include "steadylight/shading/surface_point.h"

namespace steadylight {

uint64_t CameraSeenSides::key(int object, int primitive, bool front) {
    return (uint64_t(uint32_t(object)) << 33) | (uint64_t(uint32_t(primitive)) << 1) | uint64_t(front);
}

CameraSeenSides::CameraSeenSides(const Scene& scene, const RayTracer& tracer, int columns, int rows, int max_frames) {
    const int frames = std::min(scene.frame_count(), max_frames);
    for (int k = 0; k < frames; ++k) {
        const int frame = frames > 1 ? int(int64_t(k) * (scene.frame_count() - 1) / (frames - 1)) : 0;
        const FrameState state = scene.evaluate(frame);
        const Camera& camera = state.camera;
        for (int j = 0; j < rows; ++j)
            for (int i = 0; i < columns; ++i) {
                const Ray ray = camera.generate_ray((float(i) + 0.5f) * float(camera.width) / float(columns),
                                                    (float(j) + 0.5f) * float(camera.height) / float(rows));
                if (const std::optional<Hit> hit = tracer.intersect(ray, Visibility::static_only)) {
                    const SurfacePoint sp = make_surface_point(scene, state, ray, *hit);
                    m_seen.insert(key(hit->object, hit->primitive, dot(sp.ng, ray.d) < 0));
                }
            }
    }
}

bool CameraSeenSides::seen(const Scene& scene, const FrameState& frame, const Ray& ray, const Hit& hit) const {
    if (scene.object(hit.object).is_dynamic()) return true;
    const SurfacePoint sp = make_surface_point(scene, frame, ray, hit);
    return m_seen.contains(key(hit.object, hit.primitive, dot(sp.ng, ray.d) < 0));
}

namespace {

DistantPhotonTargets find_distant_photon_targets(const Scene& scene, const RayTracer& tracer) {
    constexpr int columns = 48, rows = 36, max_frames = 16, rays_per_point = 8;
    const int frames = std::min(scene.frame_count(), max_frames);
    // Per camera ray, the crossings it found, joined in ray order: the same for any threads.
    std::vector<std::vector<std::pair<Vec3, Vec3>>> found(size_t(frames) * rows * columns);
    parallel_for_chunks(long(found.size()), 256, [&](long begin, long end) {
        for (long index = begin; index < end; ++index) {
            const int k = int(index / (rows * columns)), pixel = int(index % (rows * columns));
            const int frame = frames > 1 ? int(int64_t(k) * (scene.frame_count() - 1) / (frames - 1)) : 0;
            const FrameState state = scene.evaluate(frame);
            const Camera& camera = state.camera;
            const Ray ray = camera.generate_ray((float(pixel % columns) + 0.5f) * float(camera.width) / float(columns),
                                                (float(pixel / columns) + 0.5f) * float(camera.height) / float(rows));
            const std::optional<Hit> hit = tracer.intersect(ray, Visibility::static_only);
            if (!hit) continue;
            const SurfacePoint sp = make_surface_point(scene, state, ray, *hit);
            const Vec3 n = dot(sp.ng, ray.d) < 0 ? sp.ng : -sp.ng;  // the side the camera sees
            const auto leaves = [&](Vec3 w) {
                return !tracer.intersect(spawn_ray(sp.p, n, w), Visibility::static_only);
            };
            Pcg32 rng{uint64_t(index)};
            const OrthonormalBasis basis = OrthonormalBasis::from_normal(n);
            for (int r = 0; r < rays_per_point; ++r) {
                const Vec3 w = basis.to_world(sample_cosine_hemisphere(rng.next_vec2()));
                if (leaves(w)) found[size_t(index)].emplace_back(-w, sp.p);
            }
            for (const Vec3 sun : state.sun_directions)
                if (dot(sun, n) < 0 && leaves(-sun)) found[size_t(index)].emplace_back(sun, sp.p);
        }
    });
    std::vector<std::pair<Vec3, Vec3>> crossings;
    for (const auto& ray : found) crossings.insert(crossings.end(), ray.begin(), ray.end());
    return DistantPhotonTargets(scene.bounds(), crossings);
}

}  // namespace

std::optional<size_t> aim_distant_photons(Scene& scene) {
    if (!has_distant_light(scene.desc()) || !scene.desc().portals.empty()) return std::nullopt;
    const RayTracer tracer(scene, scene.evaluate(0));
    auto targets = std::make_shared<const DistantPhotonTargets>(find_distant_photon_targets(scene, tracer));
    const size_t marked = targets->marked_cells();
    scene.set_distant_photon_targets(std::move(targets));
    return marked;
}

std::optional<double> distant_photons_inside(const FrameContext& context, const CameraSeenSides& seen, long paths) {
    constexpr long chunk = 1024;
    std::vector<long> emitted(size_t((paths + chunk - 1) / chunk)), inside(emitted.size());
    // The photon tracer's own numbers: the estimate is of the photons the maps hold.
    parallel_for_chunks(paths, chunk, [&](long begin, long end) {
        const size_t c = size_t(begin / chunk);
        for (long i = begin; i < end; ++i) {
            PhotonSampler sampler(first_photon_index(MapKind::global) + uint64_t(i));
            const float u_select = sampler.next();
            const Vec2 u_position = sampler.next_vec2(), u_direction = sampler.next_vec2();
            const std::optional<EmissionSample> e = context.lights.sample_emission(u_select, u_position, u_direction);
            if (!e || !e->from_far_away) continue;
            ++emitted[c];
            if (is_black(e->power)) continue;
            const Ray ray{e->p, e->d};
            const std::optional<Hit> hit = context.tracer.intersect(ray);
            inside[c] += hit && seen.seen(context.scene, context.frame, ray, *hit);
        }
    });
    long total = 0, in = 0;
    for (size_t c = 0; c < emitted.size(); ++c) total += emitted[c], in += inside[c];
    if (total == 0) return std::nullopt;
    return double(in) / double(total);
}

}  // namespace steadylight
