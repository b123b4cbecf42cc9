#include "steadylight/integrators/localized.h"

#include <algorithm>

#include "steadylight/base/checkpoint.h"
#include "steadylight/base/hash.h"
#include "steadylight/base/parallel.h"
#include "steadylight/integrators/photon_gather.h"
#include "steadylight/irradiance/cache_file.h"

namespace steadylight {
namespace {

/// f(g(I)) of paper §3.3: 0 below tau_l, 1 above tau_u, a smoothstep between.
float blend_weight(float influence, const LocalizedSettings& settings) {
    const float x = std::clamp((influence - settings.tau_lower) / (settings.tau_upper - settings.tau_lower), 0.0f, 1.0f);
    return x * x * (3 - 2 * x);
}

bool same_camera(const Camera& a, const Camera& b) {
    return a.world_from_camera == b.world_from_camera && a.tan_half_fov_y == b.tan_half_fov_y;
}

/// The static records with the dynamic map's irradiance estimate added at each (paper §3.3, L_t).
IrradianceCache corrected_cache(const IrradianceCache& static_cache, const PhotonMap& dynamic, const DensitySettings& density) {
    std::vector<IrradianceRecord> records = static_cache.records();
    parallel_for_chunks(long(records.size()), 64, [&](long begin, long end) {
        for (long i = begin; i < end; ++i) {
            IrradianceRecord& r = records[size_t(i)];
            const Rgb delta = dynamic.estimate_irradiance(r.p, r.n, density);
            r.E = {std::max(0.0f, r.E.r + delta.r), std::max(0.0f, r.E.g + delta.g), std::max(0.0f, r.E.b + delta.b)};
        }
    });
    IrradianceCache corrected(static_cache.settings());
    for (const IrradianceRecord& r : records) corrected.insert(r);
    return corrected;
}

/// The influence I (paper §3.3) relative to the static indirect irradiance, at every
/// `step`-th pixel centre; the pixels between take their block's value.
struct InfluenceMap {
    int width = 0, height = 0, step = 1;
    std::vector<float> values;  // (width / step rounded up) x (height / step rounded up)

    float at(int x, int y) const {
        const int columns = (width + step - 1) / step;
        return values[size_t((y / step) * columns + x / step)];
    }
};

float relative_influence(const FrameContext& context, const PhotonMap& dynamic, const IrradianceCache& static_cache,
                         const LocalizedSettings& settings, int x, int y) {
    const std::optional<CachePoint> point = cache_point_at(context, Visibility::everything, x, y);
    if (!point) return 0;
    thread_local std::vector<Neighbour> neighbours;
    // Most of the image lies far from every dynamic photon: one nearest look-up tells.
    const float max_radius = settings.base.irradiance_estimate.max_radius;
    dynamic.k_nearest(point->p, 1, max_radius, neighbours);
    if (neighbours.empty()) return 0;
    dynamic.k_nearest(point->p, settings.influence_photons, max_radius, neighbours);
    float sum = 0;
    for (const Neighbour& nb : neighbours) {
        const Rgb& power = dynamic.photons()[nb.index].power;
        sum += std::max({std::abs(power.r), std::abs(power.g), std::abs(power.b)});
    }
    const float r2 = int(neighbours.size()) < settings.influence_photons ? max_radius * max_radius
                                                                         : neighbours.back().distance2;
    const float influence = sum / (pi * r2);
    const std::optional<Rgb> E = static_cache.interpolate(point->p, point->n, 2);
    // Scale-free: compare with the static indirect irradiance (or, where there is none, with
    // the influence itself, which then counts as large).
    const float reference = E ? max_component(*E) : 0.0f;
    return reference > 0 ? influence / reference : (influence > 0 ? infinity : 0.0f);
}

InfluenceMap estimate_influence(const FrameContext& context, const PhotonMap& dynamic, const IrradianceCache& static_cache,
                                const LocalizedSettings& settings) {
    const Camera& camera = context.frame.camera;
    InfluenceMap map{camera.width, camera.height, settings.influence_step, {}};
    const int columns = (camera.width + map.step - 1) / map.step, rows = (camera.height + map.step - 1) / map.step;
    map.values.assign(size_t(columns * rows), 0.0f);
    if (dynamic.size() == 0) return map;
    parallel_for_chunks(long(map.values.size()), 64, [&](long begin, long end) {
        for (long i = begin; i < end; ++i) {
            const int x = int(i % columns) * map.step, y = int(i / columns) * map.step;
            map.values[size_t(i)] = relative_influence(context, dynamic, static_cache, settings, x, y);
        }
    });
    return map;
}

/// What a camera ray found at its diffuse point, for the layers.
struct IndirectParts {
    float influence;
    Rgb L_y, L_t;  // irradiance
    bool on_dynamic;
};

/// The localized method's own layers: influence, L_y, L_t (as radiance) and the static cache's
/// indirect light. The last is looked up on one camera ray per pixel only (it is smooth), and
/// weighted so that the pixel's average comes out right.
void fill_layers(const FrameContext& context, const IrradianceCache& static_cache, const SurfacePoint& sp, Vec3 n,
                 const PixelSample& pixel, const IndirectParts& parts, ExtraLayers& extra) {
    const Rgb albedo_over_pi = context.bsdf_of(sp.object).diffuse_reflectance() * inv_pi;
    // Dynamic objects always take L_y: shown as the largest influence.
    extra[0] = Rgb{1, 1, 1} * (parts.on_dynamic ? 1e6f : std::min(parts.influence, 1e6f));
    extra[1] = albedo_over_pi * parts.L_y;
    extra[2] = albedo_over_pi * parts.L_t;
    if (pixel.sample == 0 && !parts.on_dynamic)
        if (const std::optional<Rgb> E = static_cache.interpolate(sp.p, n, 2))
            extra[3] = albedo_over_pi * *E * float(pixel.samples);
}

void add_geometry(Hasher& h, const Geometry& geometry) {
    if (const auto* mesh = std::get_if<TriangleMesh>(&geometry)) {
        for (const Vec3& p : mesh->positions) h.add(p);
        for (const Vec3& n : mesh->normals) h.add(n);
        for (const int index : mesh->indices) h.add(index);
    } else {
        h.add(std::get<Sphere>(geometry).center);
        h.add(std::get<Sphere>(geometry).radius);
    }
}

}  // namespace

uint64_t static_inputs_hash(const Scene& scene, int first, int last, const LocalizedSettings& settings) {
    Hasher h;
    h.add("steadylight static cache 2");  // change when the algorithm changes what it computes
    const FrameState state = scene.evaluate(first);
    for (const int i : scene.static_objects()) {
        const ObjectDesc& object = scene.object(i);
        h.add(state.world_from_object[size_t(i)]);
        add_geometry(h, object.geometry);
        const MaterialDesc& m = scene.desc().materials[size_t(object.material)];
        h.add(int(m.type)), h.add(m.reflectance), h.add(m.transmittance), h.add(m.ior), h.add(m.roughness);
        h.add(object.emission), h.add(object.two_sided_emission);
    }
    // A moving emitter lights the static scene from where it is at the segment's start.
    for (const int i : scene.dynamic_objects())
        if (scene.object(i).is_emitter()) {
            h.add(state.world_from_object[size_t(i)]), h.add(scene.object(i).emission);
            add_geometry(h, scene.object(i).geometry);
        }
    for (const PointLightDesc& light : scene.desc().point_lights) {
        h.add(int(light.type)), h.add(light.position), h.add(light.direction), h.add(light.intensity);
        h.add(light.cone_angle_deg), h.add(light.falloff_start_deg);
    }
    for (int frame = first; frame <= last; ++frame) {
        const Camera camera = scene.evaluate(frame).camera;
        h.add(camera.world_from_camera), h.add(camera.tan_half_fov_y), h.add(camera.width), h.add(camera.height);
    }
    const PhotonMappingSettings& base = settings.base;
    h.add(base.photons.global_photons), h.add(base.photons.max_bounces);
    h.add(base.irradiance_estimate.k), h.add(base.irradiance_estimate.max_radius), h.add(base.irradiance_stride);
    h.add(base.gather.theta_strata), h.add(base.gather.phi_strata), h.add(base.gather.fixed_directions);
    h.add(base.cache.accuracy), h.add(base.cache.min_spacing_px), h.add(base.cache.max_spacing_px);
    return h.value();
}

StaticSolution run_segment_pass(const Scene& scene, RayTracer& tracer, int first, int last,
                                const LocalizedSettings& settings, const std::string& cache_file) {
    const Stopwatch time;
    StaticSolution solution{IrradianceCache(settings.base.cache), 0, 0, false, ""};
    const uint64_t inputs = cache_file.empty() ? 0 : static_inputs_hash(scene, first, last, settings);
    if (!cache_file.empty()) {
        CacheFileLoad load = read_cache_file(cache_file, inputs);
        if (load.cache) {
            solution.cache = std::move(*load.cache);
            solution.records = long(solution.cache.records().size());
            solution.loaded = true;
            solution.seconds = time.elapsed_s();
            return solution;
        }
        solution.file_note = load.rejection;
    }
    const PhotonMappingSettings& base = settings.base;

    // Static photons: the complete scene's photon paths with the dynamic objects removed.
    begin_phase("static photons");
    FrameState state = scene.evaluate(first);
    tracer.set_frame(state);
    LightSet lights(scene, state);
    const auto bsdfs = make_bsdfs(scene);
    const PhotonMap static_photons = trace_photons({scene, state, tracer, lights, bsdfs}, base.photons, Visibility::static_only).global;
    const IrradiancePhotons irradiance(static_photons, base.irradiance_stride, base.irradiance_estimate);
    irradiance.compute_all();  // the static cache covers every view

    // The static cache over every distinct camera view of the segment.
    begin_phase("static cache");
    std::vector<Camera> views;
    for (int frame = first; frame <= last; ++frame) {
        state = scene.evaluate(frame);
        if (std::any_of(views.begin(), views.end(), [&](const Camera& c) { return same_camera(c, state.camera); })) continue;
        views.push_back(state.camera);
        tracer.set_frame(state);
        const FrameContext context{scene, state, tracer, lights, bsdfs};
        build_photon_cache(solution.cache, {context, irradiance, base.irradiance_estimate.max_radius, base.gather,
                                            Visibility::static_only, {}});
    }
    solution.records = long(solution.cache.records().size());
    if (!cache_file.empty()) write_cache_file(cache_file, solution.cache, inputs);
    solution.seconds = time.elapsed_s();
    return solution;
}

LocalizedFrame render_localized(const FrameContext& context, const StaticSolution& solution,
                                const LocalizedSettings& settings) {
    const Stopwatch total;
    const PhotonMappingSettings& base = settings.base;
    LocalizedFrame out;
    FrameStats& stats = out.stats;
    stats.method = settings.frozen ? "frozen" : "localized";
    stats.frame = context.frame.frame;
    stats.static_records = solution.records;

    // Photons in the complete scene: the global, caustic and dynamic maps.
    const FramePhotons traced(context, base, stats);
    const TracedPhotons& photons = traced.maps;
    const IrradiancePhotons& irradiance = traced.irradiance;

    // Influence of the dynamic objects on each pixel's point.
    begin_phase("influence");
    Stopwatch phase;
    const InfluenceMap influence = settings.frozen ? InfluenceMap{} : estimate_influence(context, photons.dynamic, solution.cache, settings);
    stats.influence_s = phase.elapsed_s();

    // L_y: the dynamic cache, only where the influence is felt and on dynamic objects.
    begin_phase("L_y");
    phase = Stopwatch();
    IrradianceCache dynamic_cache(base.cache);
    const float max_radius = base.irradiance_estimate.max_radius;
    const auto wanted = [&](const CachePoint& point, int x, int y) {
        return context.scene.object(point.object).is_dynamic() ||
               (!settings.frozen && influence.at(x, y) > settings.tau_lower);
    };
    const CacheBuildStats built = build_photon_cache(dynamic_cache, {context, irradiance, max_radius, base.gather, Visibility::everything, wanted});
    stats.cache_s = phase.elapsed_s();
    stats.irradiance_records = built.records_added;

    // L_t: the static records corrected by the dynamic map.
    begin_phase("L_t");
    phase = Stopwatch();
    const IrradianceCache& static_cache = solution.cache;
    const IrradianceCache corrected = settings.frozen ? IrradianceCache(base.cache)
                                                      : corrected_cache(static_cache, photons.dynamic, settings.correction_estimate);
    const IrradianceCache& transported = settings.frozen ? static_cache : corrected;
    stats.correction_s = phase.elapsed_s();

    // Shade: L_i = f(g(I)) L_y + (1 - f(g(I))) L_t, and L_y on dynamic objects.
    begin_phase("shading");
    phase = Stopwatch();
    const auto gather = make_point_gather(context, irradiance, max_radius, base.gather);
    std::atomic<long> fallbacks = 0, gather_rays = 0;
    const auto indirect = [&](const SurfacePoint& sp, Vec3 n, const PixelSample& pixel, ExtraLayers* extra) {
        const bool on_dynamic = context.scene.object(sp.object).is_dynamic();
        const float I = on_dynamic || influence.values.empty() ? 0.0f : influence.at(pixel.x, pixel.y);
        const float weight = on_dynamic ? 1.0f : (settings.frozen ? 0.0f : blend_weight(I, settings));
        const auto [L_y, L_t, unused] = remembered(pixel.memo, pixel.reach, sp, n, [&] {
            return PixelMemo::Values{
                weight > 0 ? cached_irradiance(dynamic_cache, sp, n, gather, fallbacks, gather_rays) : Rgb{},
                weight < 1 ? cached_irradiance(transported, sp, n, gather, fallbacks, gather_rays) : Rgb{}, Rgb{}};
        });
        if (extra) fill_layers(context, static_cache, sp, n, pixel, {I, L_y, L_t, on_dynamic}, *extra);
        return L_y * weight + L_t * (1 - weight);
    };
    ShadedFrame shaded = shade_frame(context, base.shading, photons.caustic, indirect);
    stats.direct_s = phase.elapsed_s();
    stats.caustics_s = shaded.caustic_cpu_s;
    stats.fallback_gathers = fallbacks;
    stats.gather_rays = built.gather_rays + gather_rays;

    take_common_layers(shaded, out);
    out.influence = std::move(shaded.extra[0]);
    out.L_y = std::move(shaded.extra[1]);
    out.L_t = std::move(shaded.extra[2]);
    out.indirect_static = std::move(shaded.extra[3]);
    out.static_records = record_picture(context.frame.camera, static_cache.records());
    out.dynamic_records = record_picture(context.frame.camera, dynamic_cache.records());
    stats.irradiance_photons = irradiance.computed();
    stats.total_s = total.elapsed_s();
    return out;
}

}  // namespace steadylight
