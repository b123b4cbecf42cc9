// The segment pass: static photons and the static cache (segment_pass.h).
#include "steadylight/passes/segment_pass.h"

#include <algorithm>
#include <optional>
#include <vector>

#include "steadylight/base/checkpoint.h"
#include "steadylight/base/hash.h"
#include "steadylight/passes/photon_gather.h"
#include "steadylight/photons/surface_coverage.h"

namespace steadylight {
namespace {

bool same_camera(const Camera& a, const Camera& b) {
    return a.world_from_camera == b.world_from_camera && a.tan_half_fov_y == b.tan_half_fov_y;
}

void add_geometry(Hasher& h, const Geometry& geometry) {
    if (const auto* mesh = std::get_if<TriangleMesh>(&geometry)) {
        for (const Vec3& p : mesh->positions) h.add(p);
        for (const Vec3& n : mesh->normals) h.add(n);
        for (const int index : mesh->indices) h.add(index);
        for (const auto* uv : {&mesh->uv0, &mesh->uv1})
            for (const Vec2& t : *uv) h.add(t.x), h.add(t.y);
        for (const auto* values : {&mesh->colors, &mesh->tangents})
            for (const Rgba& c : *values)
                for (const float x : c) h.add(x);
    } else {
        h.add(std::get<Sphere>(geometry).center);
        h.add(std::get<Sphere>(geometry).radius);
    }
}

}  // namespace

uint64_t static_inputs_hash(const Scene& scene, const Segment& segment, const PhotonMappingSettings& settings) {
    Hasher h;
    h.add("steadylight static cache 3");  // change when the algorithm changes what it computes
    const FrameState state = scene.evaluate(segment.first);
    for (const int i : scene.static_objects()) {
        const ObjectDesc& object = scene.object(i);
        h.add(state.world_from_object[size_t(i)]);
        add_geometry(h, object.geometry);
        const MaterialDesc& m = scene.desc().materials[size_t(object.material)];
        h.add(int(m.type)), h.add(m.reflectance), h.add(m.transmittance), h.add(m.ior), h.add(m.roughness);
        h.add(m.metallic), h.add(m.specular), h.add(m.specular_color), h.add(m.alpha), h.add(int(m.alpha_mode));
        h.add(m.alpha_cutoff), h.add(m.normal_scale);
        if (const Rgb sigma = m.absorption(); !is_black(sigma)) h.add(sigma);  // older keys stay valid without one
        for (const TextureRef* t :
             {&m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture, &m.emissive_texture}) {
            h.add(t->image), h.add(t->texcoord), h.add(int(t->wrap_s)), h.add(int(t->wrap_t)), h.add(int(t->filter));
            for (const float x : {t->offset.x, t->offset.y, t->rotation, t->scale.x, t->scale.y}) h.add(x);
            if (t->is_set()) {
                const TextureImage& image = scene.desc().images[size_t(t->image)];
                h.add(image.width), h.add(image.height), h.add(image.rgba.data(), image.rgba.size());
            }
        }
        // The emission at the segment's start: it is constant within the segment (segments split
        // where a light is switched or dimmed), so a cache of the light off never serves it on.
        h.add(state.emission[size_t(i)]), h.add(object.two_sided_emission);
    }
    // An emitter that moves lights no static record, but its power shares out the photons; one that
    // changes size is a segment per frame, lighting the static scene from where it is then.
    for (const int i : scene.dynamic_objects())
        if (scene.object(i).is_emitter()) {
            h.add(state.world_from_object[size_t(i)]), h.add(state.emission[size_t(i)]);
            add_geometry(h, scene.object(i).geometry);
        }
    // A lamp or sun that moves lights no static record, but its power shares out the photons.
    for (size_t i = 0; i < scene.desc().point_lights.size(); ++i) {
        const PointLightDesc& light = scene.desc().point_lights[i];
        const PointLightPose& pose = state.point_lights[i];
        h.add(int(light.type)), h.add(light.is_moving()), h.add(pose.intensity);
        if (!light.is_moving()) h.add(pose.position), h.add(pose.direction);
        h.add(light.cone_angle_deg), h.add(light.falloff_start_deg);
    }
    for (size_t i = 0; i < scene.desc().suns.size(); ++i) {
        const SunLightDesc& sun = scene.desc().suns[i];
        h.add(sun.is_moving()), h.add(sun.irradiance), h.add(sun.angle_deg);
        if (!sun.is_moving()) h.add(state.sun_directions[i]);
    }
    if (const std::optional<WorldDesc>& world = scene.desc().world) h.add(world->radiance->hash());
    for (const PortalDesc& portal : scene.desc().portals)
        h.add(portal.corner), h.add(portal.edge_u), h.add(portal.edge_v);
    // Light from far away aims its photons at the animation's bounds.
    if (!scene.desc().suns.empty() || scene.desc().world) h.add(scene.bounds().center), h.add(scene.bounds().radius);
    if (const DistantPhotonTargets* targets = scene.distant_photon_targets()) h.add(targets->hash());
    for (int frame = segment.first; frame <= segment.last; ++frame) {
        const Camera camera = scene.evaluate(frame).camera;
        h.add(camera.world_from_camera), h.add(camera.tan_half_fov_y), h.add(camera.width), h.add(camera.height);
    }
    h.add(settings.photons.global_photons), h.add(settings.photons.max_bounces);
    h.add(settings.irradiance_estimate.k), h.add(settings.irradiance_estimate.max_radius),
        h.add(settings.irradiance_stride);
    // Raised whenever the estimate at the photons changes what it computes, so that cache files
    // made by an older steadylight are not taken for this one's. 2: unbiased and boundary-corrected;
    // 3: photons the surface does not reach left out (lamp housings);
    // 4: one in `stride` photons chosen by their hash, their probes turned by it.
    constexpr int photon_irradiance_revision = 4;
    h.add(photon_irradiance_revision);
    h.add(settings.gather.theta_strata), h.add(settings.gather.phi_strata), h.add(settings.gather.fixed_directions);
    h.add(max_gather_chain);
    h.add(settings.cache.accuracy), h.add(settings.cache.min_spacing_px), h.add(settings.cache.max_spacing_px);
    return h.value();
}

IrradianceCache run_segment_pass(const Scene& scene, RayTracer& tracer, const Segment& segment,
                                 const PhotonMappingSettings& settings, const StaticPhotonPaths* paths) {
    const Bsdfs bsdfs = make_bsdfs(scene);

    // Static photons: the complete scene's photon paths with the dynamic objects removed.
    begin_phase("static photons");
    std::optional<PlacedFrame> start(std::in_place, scene, tracer, bsdfs, segment.first);
    PhotonMap traced;
    if (!paths) traced = trace_photons(start->context(), settings.photons, Visibility::static_only).global;
    const PhotonMap& static_photons = paths ? paths->global.photons : traced;
    std::optional<IrradiancePhotons> own;
    const IrradiancePhotons& irradiance =
        paths && paths->irradiance
            ? *paths->irradiance
            : own.emplace(static_photons, settings.irradiance_stride, settings.irradiance_estimate,
                          surface_coverage(start->context(), Visibility::static_only));
    irradiance.compute_all();  // the static cache covers every view; frames take them where nothing changed
    start.reset();             // the views below place the tracer anew

    // The static cache over every distinct camera view of the segment.
    begin_phase("static cache");
    IrradianceCache cache(settings.cache);
    for (const int frame : distinct_views(scene, segment)) {
        const PlacedFrame view(scene, tracer, bsdfs, frame);
        build_photon_cache(cache, {view.context(),
                                   irradiance,
                                   settings.irradiance_estimate.max_radius,
                                   settings.gather,
                                   Visibility::static_only,
                                   {}});
    }
    return cache;
}

std::vector<int> distinct_views(const Scene& scene, const Segment& segment) {
    std::vector<int> frames;
    std::vector<Camera> views;
    for (int frame = segment.first; frame <= segment.last; ++frame) {
        const Camera camera = scene.evaluate(frame).camera;
        if (std::any_of(views.begin(), views.end(), [&](const Camera& c) { return same_camera(c, camera); })) continue;
        views.push_back(camera);
        frames.push_back(frame);
    }
    return frames;
}

std::shared_ptr<const StaticPhotonPaths> trace_segment_photon_paths(const Scene& scene, RayTracer& tracer,
                                                                    const Segment& segment,
                                                                    const PhotonMappingSettings& settings) {
    begin_phase("static photon paths");
    const Bsdfs bsdfs = make_bsdfs(scene);
    const PlacedFrame start(scene, tracer, bsdfs, segment.first);
    auto paths = std::make_shared<StaticPhotonPaths>(trace_static_photon_paths(start.context(), settings.photons));
    // The coverage keeps the scene and the tracer, and the static objects stay where they are.
    paths->irradiance = std::make_shared<const IrradiancePhotons>(
        paths->global.photons, settings.irradiance_stride, settings.irradiance_estimate,
        surface_coverage(start.context(), Visibility::static_only));
    return paths;
}

}  // namespace steadylight
