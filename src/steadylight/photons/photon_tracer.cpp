#include "steadylight/photons/photon_tracer.h"

#include <vector>

#include "steadylight/base/parallel.h"
#include "steadylight/base/settings_check.h"
#include "steadylight/photons/photon_paths.h"
#include "steadylight/shading/surface_point.h"

namespace steadylight {

void PhotonTracer::trace(uint64_t index, PhotonGroup group, float scale, PhotonOutput out) const {
    PhotonSampler sampler(index);
    const float u_select = sampler.next();
    const Vec2 u_position = sampler.next_vec2();
    const Vec2 u_direction = sampler.next_vec2();
    const std::optional<EmissionSample> e = emit(group, u_select, u_position, u_direction);
    if (!e || is_black(e->power)) return;
    // Photons from area lights leave the surface; point lights have no surface to leave.
    const Ray ray = length2(e->n) > 0 ? spawn_ray(e->p, e->n, e->d) : Ray{e->p, e->d};
    PhotonPath path{ray, e->power * scale, sampler};
    // The static pass holds none of a moving light's light: its photons are change from the start
    // (their indirect hits go to the dynamic map, and there is no static path to take back).
    path.dynamic = group == PhotonGroup::moving;
    follow(path, out);
}

void PhotonTracer::resume(uint64_t index, const PathSegment& segment, int bounce, PhotonOutput out) const {
    follow({Ray{segment.o, segment.d}, segment.power, PhotonSampler::at_bounce(index, bounce), bounce,
            segment.specular_path},
           out);
}

/// A photon's start: aimed at the caustic targets where that pays, else as its light emits.
std::optional<EmissionSample> PhotonTracer::emit(PhotonGroup group, float u_select, Vec2 u_position,
                                                 Vec2 u_direction) const {
    const LightSet& lights = m_context.lights;
    if (m_targets) {
        const std::optional<EmissionPoint> at = lights.sample_emission_point(group, u_select, u_position);
        // Lights from far away are never aimed (their points have no pdf).
        const std::optional<AimedDirection> aim =
            at && at->pdf > 0 ? m_targets->sample(at->p, u_direction) : std::nullopt;
        if (aim) {
            const Vec3 n = dot(at->n, aim->d) < 0 ? -at->n : at->n;  // the side it leaves
            return EmissionSample{at->p, n, aim->d, lights.emitted_intensity(*at, aim->d) / (at->pdf * aim->pdf)};
        }
    }
    return lights.sample_emission(group, u_select, u_position, u_direction);
}

void PhotonTracer::store(const PhotonPath& path, const Photon& photon, PhotonOutput out) const {
    const bool direct = path.bounce == 0;
    // Negative photons belong to the dynamic map only; the others to their own map.
    if (!path.negative && (m_kind == MapKind::global || path.specular_path)) out.main.push_back(photon);
    // Direct hits stay out of the dynamic map: direct light is ray traced (paper §3.1, a b g).
    // So do caustic photons (every bounce before specular or glossy): the frame's caustic map
    // holds their change already.
    if (out.dynamic && path.dynamic && !direct && !path.specular_path) out.dynamic->push_back(photon);
}

void PhotonTracer::follow(PhotonPath path, PhotonOutput out) const {
    for (; path.bounce < m_settings.max_bounces; ++path.bounce) {
        // Negative photons live in the static scene: they pass through every dynamic object.
        const Visibility visibility = path.negative ? Visibility::static_only : m_visibility;
        const std::optional<Hit> hit = m_context.tracer.intersect(path.ray, visibility);
        // Kept with the power it starts with: the glass absorption along it depends on where it
        // ends, which a dynamic object can change, so a resumed path applies it itself.
        if (out.segments)
            out.segments->push_back({path.ray.o, path.ray.d, hit ? hit->t : infinity, path.power, path.specular_path});
        if (!hit) return;
        const SurfacePoint sp = make_surface_point(m_context.scene, m_context.frame, path.ray, *hit);

        // The first dynamic hit: from here the path differs from the static one, which a
        // negative photon follows on with the same ray and the same random numbers.
        if (out.dynamic && !path.dynamic && m_context.scene.object(sp.object).is_dynamic()) {
            if (out.negatives) {
                PhotonPath negative = path;
                negative.dynamic = negative.negative = true;
                negative.power = path.power * -1.0f;
                follow(negative, out);
            }
            path.dynamic = true;
        }

        // A segment that crossed absorbing glass lost some of its power on the way.
        const Rgb absorbed = volume_transmittance(m_context, sp, path.ray.d, hit->t);
        const SurfaceBsdf surface_bsdf = bsdf_at(m_context, sp);
        const Bsdf* bsdf = &*surface_bsdf;
        std::unique_ptr<Bsdf> glossy_part;
        const Vec3 arrival_n = dot(sp.ng, path.ray.d) < 0 ? sp.ng : -sp.ng;
        if (bsdf->is_diffuse()) {
            store(path, {sp.p, arrival_n, -path.ray.d, path.power, uint16_t(path.bounce)}, out);
            // A caustic path ends at its first diffuse hit, except that one arriving straight
            // from a light goes on along a coat's glossy lobes (light a varnished floor reflects).
            if (m_kind == MapKind::caustic) {
                if (path.bounce > 0 || !(glossy_part = bsdf->non_diffuse_part())) return;
                bsdf = glossy_part.get();
            }
        }

        // Scatter, or be absorbed (by the surface or the glass behind it): survive with the
        // probability of the scattered power. Always these four numbers, whatever happens next:
        // resumed paths rely on it (photon_tracer.h).
        const OrthonormalBasis basis = OrthonormalBasis::from_normal(sp.nm);
        const float u_lobe = path.sampler.next(), u_survive = path.sampler.next();
        const std::optional<BsdfSample> bs =
            bsdf->sample(basis.to_local(-path.ray.d), path.sampler.next_vec2(), u_lobe, TransportMode::importance);
        if (!bs) return;
        const Rgb throughput = bs->weight * absorbed;
        const float survive = std::min(1.0f, max_component(throughput));
        if (!(u_survive < survive)) return;
        path.power *= throughput / survive;
        // A bounce off a coat's or a metal's glossy lobe keeps a path caustic; one drawn from a
        // diffuse base ends that (docs/materials.md, "The photon method").
        path.specular_path = (path.bounce == 0 || path.specular_path) && !bs->diffuse;
        path.ray = spawn_ray(sp.p, sp.ng, basis.to_world(bs->wi));
    }
}

TracedPaths trace_paths(const PhotonTracer& tracer, MapKind kind, PhotonSplit split, long begin, long end,
                        bool dynamic) {
    // Chunks store into their own vectors, joined in chunk order: the same maps for any threads.
    constexpr long chunk = 4096;
    const long count = std::max(end - begin, 0L);
    const size_t chunks = size_t((count + chunk - 1) / chunk);
    std::vector<std::vector<Photon>> main(chunks), dynamic_photons(chunks);
    parallel_for_chunks(count, chunk, [&](long chunk_begin, long chunk_end) {
        const size_t c = size_t(chunk_begin / chunk);
        const PhotonOutput out{main[c], dynamic ? &dynamic_photons[c] : nullptr};
        for (long i = begin + chunk_begin; i < begin + chunk_end; ++i) {
            const PhotonGroup group = split.group_of(i);
            tracer.trace(first_photon_index(kind) + uint64_t(i), group, 1.0f / float(split.count(group)), out);
        }
    });
    return {join(main), join(dynamic_photons)};
}

namespace {

/// The photons of `count` paths of one kind, and of the dynamic map when `dynamic` is set. The
/// static scene (Visibility::static_only) holds the still lights' photons only.
std::pair<PhotonMap, PhotonMap> trace_map(const FrameContext& context, long count, MapKind kind,
                                          const PhotonSettings& settings, Visibility visibility, bool dynamic) {
    if (count <= 0 || context.lights.empty()) return {};
    const PhotonSplit split = context.lights.split(count);
    const long traced = visibility == Visibility::static_only ? split.still : count;
    const std::optional<CausticTargets> targets =
        kind == MapKind::caustic ? std::optional<CausticTargets>(std::in_place, context, visibility) : std::nullopt;
    const PhotonTracer tracer(context, settings, kind, visibility, targets ? &*targets : nullptr);
    TracedPaths paths = trace_paths(tracer, kind, split, 0, traced, dynamic);
    return {PhotonMap(std::move(paths.main), traced), PhotonMap(std::move(paths.dynamic), dynamic ? traced : 0)};
}

}  // namespace

bool has_non_diffuse_surface(const FrameContext& context) {
    for (int object = 0; object < int(context.scene.objects().size()); ++object) {
        const Bsdf& bsdf = context.bsdf_of(object);
        if (!bsdf.is_diffuse() || bsdf.non_diffuse_part()) return true;
        // A textured material may be metallic or coated somewhere even if its factors say not.
        const MaterialDesc& m = context.scene.desc().materials[size_t(context.scene.object(object).material)];
        if (m.type == MaterialType::pbr && m.metallic_roughness_texture.is_set() && m.metallic > 0) return true;
    }
    return false;
}

bool has_dynamic_map(const FrameContext& context) {
    return !context.scene.dynamic_objects().empty() || context.lights.has_moving();
}

TracedPhotons trace_photons(const FrameContext& context, const PhotonSettings& settings, Visibility visibility) {
    const bool dynamic = visibility == Visibility::everything && has_dynamic_map(context);
    auto [global, dynamic_map] =
        trace_map(context, settings.global_photons, MapKind::global, settings, visibility, dynamic);
    const long caustic_count = has_non_diffuse_surface(context) ? settings.caustic_photons : 0;
    auto [caustic, unused] = trace_map(context, caustic_count, MapKind::caustic, settings, visibility, false);
    return {std::move(global), std::move(caustic), std::move(dynamic_map)};
}

void validate(const PhotonSettings& settings, const std::string& where) {
    check_setting_range(where + "/global_photons", settings.global_photons, 0L, 1L << 34);
    check_setting_range(where + "/caustic_photons", settings.caustic_photons, 0L, 1L << 34);
    check_setting_range(where + "/max_bounces", settings.max_bounces, 0, 1000);
}

}  // namespace steadylight
