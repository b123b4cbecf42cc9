#include "steadylight/passes/shading_pass.h"

#include <algorithm>

#include "steadylight/base/check.h"
#include "steadylight/base/parallel.h"
#include "steadylight/base/rng.h"
#include "steadylight/base/sampling.h"
#include "steadylight/base/settings_check.h"
#include "steadylight/base/stopwatch.h"
#include "steadylight/passes/kept_direct_light.h"
#include "steadylight/passes/photon_gather.h"
#include "steadylight/shading/surface_point.h"

namespace steadylight {
namespace {

/// Delta bounces up to this depth follow every lobe (glass: reflection and refraction).
constexpr int max_split_depth = 2;
/// Bounces followed from a glossy surface the camera sees directly.
constexpr int glossy_camera_bounces = 4;

/// The lighting along a camera ray split the way the EXR's layers are.
using Components = PixelSums;

/// Whether a ray counts the emission it meets: not where the surface it left sampled the
/// lights (a glossy bounce), nor after one reflection in a flat mirror from there, whose
/// light the glossy point sampled too (mirror_images.h).
enum class Emission { counted, sampled, sampled_in_mirror };

/// Which of a pixel's light samples a camera ray takes: sample k of this ray is number
/// first + k of `count`, stratified over the pixel (base/sampling.h stratified_2d), so the
/// shadow rays of all the pixel's camera rays together cover the lights evenly.
struct LightStrata {
    uint32_t first = 0;
    uint32_t count = 1;
    Vec2 shift;

    Vec2 sample(int k) const { return stratified_2d(first + uint32_t(k), count, shift); }
};

/// The random-number streams of a pixel (docs/localized.md, "Random numbers per term"): one for
/// the pixel's own constants (the jitter of its camera rays and of its light strata) and one per
/// camera ray for the lobes its path chooses (specular chains, a coat's bounce). The direct
/// light takes its numbers from the light strata, none from a stream. So no term, and no camera
/// ray, depends on what another consumed: a frame can redo one term of one ray alone.
enum class PixelStream : uint64_t { constants = 0x9e01, path = 0x9e02 };

Pcg32 pixel_stream(const Camera& camera, int x, int y, PixelStream stream, int sample = 0) {
    return Pcg32(hash_ids(uint64_t(y) * uint64_t(camera.width) + uint64_t(x), uint64_t(stream), uint64_t(sample)));
}

/// Records where a camera ray's indirect light came from: its look-up (the pixel memo's entry)
/// and the albedo that multiplied it. A ray whose value the memo did not keep, or whose layers
/// show another albedo (fill_layers takes the one seen head-on), marks its pixel `unkept`.
void record_look_up(const PixelSample& pixel, const Bsdf& bsdf, Rgb albedo_over_pi) {
    const int entry = pixel.memo ? pixel.memo->last_used() : -1;
    if (entry < 0 || bsdf.diffuse_reflectance({0, 0, 1}) * inv_pi != albedo_over_pi) {
        pixel.recorder->add_flags(pixel.pixel_index, PixelRecorder::unkept);
        return;
    }
    const auto [p, n] = pixel.memo->point_of(entry);
    pixel.recorder->add_look_up(pixel.pixel_index, pixel.sample, entry, p, n, albedo_over_pi);
}

class Shader {
public:
    Shader(const FrameContext& context, const ShadingSettings& settings, const PhotonMap& caustic,
           const IndirectIrradiance& indirect, const ReflectedRadiance& reflected, Visibility visibility,
           int extra_layers)
        : m_context(context),
          m_settings(settings),
          m_caustic(caustic),
          m_indirect(indirect),
          m_reflected(reflected),
          m_visibility(visibility),
          m_extra_layers(extra_layers) {}

    Components shade(const Ray& ray, int depth, Emission emission, const PixelSample& pixel, const LightStrata& strata,
                     Pcg32& rng) const;
    double caustic_cpu_s() const { return double(m_caustic_ns) * 1e-9; }

private:
    Components shade_hit(const Ray& ray, const Hit& hit, const SurfacePoint& surface, int depth, Emission emission,
                         const PixelSample& pixel, const LightStrata& strata, Pcg32& rng) const;
    Rgb direct_light(const SurfacePoint& sp, const OrthonormalBasis& basis, const Bsdf& bsdf, Vec3 wo,
                     const LightStrata& strata, const PixelSample& pixel) const;
    /// Notes for pixel reuse a shadow ray towards a light from far away that reached it.
    void record_distant(const PixelSample& pixel, const LightSample& light) const;
    Rgb light_in_mirrors(const SurfacePoint& sp, const OrthonormalBasis& basis, const Bsdf& bsdf, Vec3 wo,
                         const LightStrata& strata, const PixelSample& pixel) const;
    bool is_flat_mirror(int object) const;
    Rgb trace_coat(const Bsdf& coat, const SurfacePoint& surface, const Ray& ray, Pcg32& rng) const;
    void shade_diffuse(const SurfacePoint& sp, const OrthonormalBasis& basis, const Bsdf& bsdf, Vec3 wo, int depth,
                       const PixelSample& pixel, const LightStrata& strata, Components& c) const;

    const FrameContext& m_context;
    const ShadingSettings& m_settings;
    const PhotonMap& m_caustic;
    const IndirectIrradiance& m_indirect;
    const ReflectedRadiance& m_reflected;
    const Visibility m_visibility;  // static_only: the static frame, with the dynamic objects removed
    const int m_extra_layers;       // how many of the method's own layers shade_frame() pictures
    mutable std::atomic<long> m_caustic_ns = 0;
};

void Shader::record_distant(const PixelSample& pixel, const LightSample& light) const {
    if (pixel.recorder && std::isinf(light.distance))
        pixel.recorder->add_distant_direction(pixel.pixel_index, light.wi);
}

Rgb Shader::direct_light(const SurfacePoint& sp, const OrthonormalBasis& basis, const Bsdf& bsdf, Vec3 wo,
                         const LightStrata& strata, const PixelSample& pixel) const {
    Rgb sum;
    if (pixel.direct_log) pixel.direct_log->add_ray(sp.p, sp.ng);
    for (int s = 0; s < m_settings.direct_samples; ++s) {
        // Stratified: the choice of light takes the stratified dimension and passes its
        // remainder on, so each light's area is stratified too, not only the pixel's samples.
        // Lights are chosen by what they could give this point (no MIS here to agree with).
        const std::optional<LightSample> light = m_context.lights.sample_reusing(sp.p, sp.ns, strata.sample(s));
        if (!light) continue;
        const Vec3 wi = basis.to_local(light->wi);
        const Rgb f = bsdf.eval(wo, wi);
        if (is_black(f)) continue;
        const Ray shadow = shadow_ray(*light, sp.p, sp.ng);
        const Rgb value = f * light->Li * (std::abs(wi.z) / light->pdf);
        if (pixel.direct_log) {
            // occluded()'s two queries apart: what the static objects stop stays stopped through
            // the segment, so only the other samples are kept, for frames that ask the dynamic
            // objects alone.
            if (m_context.tracer.occluded(shadow, Visibility::static_only)) continue;
            const bool distant = std::isinf(light->distance);
            pixel.direct_log->add_sample(distant ? light->wi : light->p, distant, value);
            if (m_context.tracer.occluded_by_dynamic(shadow)) continue;
        } else if (m_context.tracer.occluded(shadow, m_visibility)) {
            continue;
        }
        record_distant(pixel, *light);
        sum += value;
    }
    return sum / float(m_settings.direct_samples);
}

/// Light reaching glossy point `sp` by one reflection in a flat static mirror (mirror_images.h):
/// the lights sampled as seen from the point's mirror image, with direct_light's strata.
Rgb Shader::light_in_mirrors(const SurfacePoint& sp, const OrthonormalBasis& basis, const Bsdf& bsdf, Vec3 wo,
                             const LightStrata& strata, const PixelSample& pixel) const {
    Rgb sum;
    for (const MirrorPlane& mirror : m_context.mirrors) {
        const float side = dot(sp.p - mirror.point, mirror.normal);
        if (std::abs(side) <= ray_epsilon(sp.p)) continue;
        const auto mirrored = [&](Vec3 v) { return v - mirror.normal * (2 * dot(v, mirror.normal)); };
        const Vec3 image = sp.p - mirror.normal * (2 * side);
        for (int s = 0; s < m_settings.direct_samples; ++s) {
            const std::optional<LightSample> light =
                m_context.lights.sample_reusing(image, mirrored(sp.ns), strata.sample(s));
            // A light behind the mirror's plane has no image on this side.
            if (!light || dot(light->p - mirror.point, mirror.normal) * side <= 0) continue;
            const Vec3 towards_image = mirrored(light->wi);
            const Vec3 wi = basis.to_local(towards_image);
            const Rgb f = bsdf.eval(wo, wi);
            const float t_plane = side / -dot(towards_image, mirror.normal);
            if (is_black(f) || !(t_plane > 0)) continue;
            // The path's reflection lies on the plane: the mirror must be the first surface there.
            if (pixel.recorder) pixel.recorder->add_point(pixel.pixel_index, sp.p + towards_image * t_plane);
            const Ray to_mirror = spawn_ray(sp.p, sp.ng, towards_image);
            const std::optional<Hit> hit = m_context.tracer.intersect(to_mirror, m_visibility);
            if (!hit || hit->object != mirror.object) continue;
            const SurfacePoint on_mirror = make_surface_point(m_context.scene, m_context.frame, to_mirror, *hit);
            const std::optional<Bounce> reflected =
                sample_bounce(*bsdf_at(m_context, on_mirror), on_mirror, towards_image, {}, 0, TransportMode::radiance);
            if (!reflected || m_context.tracer.occluded(shadow_ray(*light, on_mirror.p, on_mirror.ng), m_visibility))
                continue;
            record_distant(pixel, *light);
            sum += f * reflected->sample.weight * light->Li * (std::abs(wi.z) / light->pdf);
        }
    }
    return sum / float(m_settings.direct_samples);
}

bool Shader::is_flat_mirror(int object) const {
    return std::any_of(m_context.mirrors.begin(), m_context.mirrors.end(),
                       [object](const MirrorPlane& mirror) { return mirror.object == object; });
}

void Shader::shade_diffuse(const SurfacePoint& sp, const OrthonormalBasis& basis, const Bsdf& bsdf, Vec3 wo, int depth,
                           const PixelSample& pixel, const LightStrata& strata, Components& c) const {
    // Textures multiply here, after the cache's interpolation: they are never blurred by it.
    const Rgb albedo_over_pi = bsdf.diffuse_reflectance(wo) * inv_pi;
    if (!pixel.skip_direct) c.direct += direct_light(sp, basis, bsdf, wo, strata, pixel);
    c.indirect = albedo_over_pi * m_indirect(sp, sp.ns, pixel, depth == 0 && m_extra_layers > 0 ? &c.extra : nullptr);
    if (depth == 0 && pixel.recorder) record_look_up(pixel, bsdf, albedo_over_pi);
    // A diffuse point reads the caustic map, an empty one too: a frame's may not be empty.
    if (pixel.recorder) pixel.recorder->add_flags(pixel.pixel_index, PixelRecorder::reads_caustics);
    if (m_caustic.size() == 0) return;  // no specular surface lit: no caustics, nothing to time
    const Stopwatch caustic_time;
    // A caustic estimate is reused by the pixel's other camera rays only where it is smoother than
    // the pixel (its radius at least the reach): a sharper one is estimated at each ray's own
    // point, so that the pixel averages it over its area as the path tracer does, instead of
    // taking one point of it.
    const PixelMemo::Values* known = pixel.caustic_memo ? pixel.caustic_memo->find(sp, sp.ng, pixel.reach) : nullptr;
    if (known) {
        c.caustic = albedo_over_pi * (*known)[0];
    } else {
        float radius = 0;
        const Rgb E = m_caustic.estimate_irradiance_cone(sp.p, sp.ng, m_settings.caustic_estimate, &radius);
        if (pixel.caustic_memo && radius >= pixel.reach) pixel.caustic_memo->add(sp, sp.ng, {E});
        c.caustic = albedo_over_pi * E;
    }
    m_caustic_ns += long(caustic_time.elapsed_s() * 1e9);
}

/// The indirect light a coat over a diffuse base reflects: one sampled bounce, whose radiance
/// the photons give (its direct light came with the BSDF's own light sampling).
Rgb Shader::trace_coat(const Bsdf& coat, const SurfacePoint& surface, const Ray& ray, Pcg32& rng) const {
    const float u_lobe = rng.next_float();
    const std::optional<Bounce> bounce =
        sample_bounce(coat, surface, ray.d, rng.next_vec2(), u_lobe, TransportMode::radiance);
    if (!bounce) return {};
    return bounce->sample.weight * m_reflected(bounce->ray);
}

Components Shader::shade(const Ray& ray, int depth, Emission emission, const PixelSample& pixel,
                         const LightStrata& strata, Pcg32& rng) const {
    const std::optional<Hit> hit = m_context.tracer.intersect(ray, m_visibility);
    if (pixel.recorder && depth > 0)
        pixel.recorder->add_flags(pixel.pixel_index,
                                  hit ? PixelRecorder::chain : PixelRecorder::chain | PixelRecorder::open_chain);
    if (!hit) {
        if (pixel.direct_log) pixel.direct_log->spoil();
        // The lights from far away, seen as an emitter is (light sampling took them otherwise);
        // a transparent background leaves out what the camera sees of them directly.
        Components c;
        const bool hidden = depth == 0 && m_context.frame.camera.transparent_background;
        if (emission == Emission::counted && !pixel.skip_direct && !hidden)
            c.direct = m_context.lights.escaped_radiance(ray.d);
        return c;
    }
    const SurfacePoint surface = make_surface_point(m_context.scene, m_context.frame, ray, *hit);
    if (pixel.recorder) pixel.recorder->add_point(pixel.pixel_index, surface.p);
    Components c = shade_hit(ray, *hit, surface, depth, emission, pixel, strata, rng);
    c.covered = 1;
    // Light from a hit inside absorbing glass crossed its volume (the AOV layers are not light).
    const Rgb absorbed = volume_transmittance(m_context, surface, ray.d, hit->t);
    if (absorbed != Rgb{1, 1, 1} && pixel.direct_log) pixel.direct_log->spoil();
    if (absorbed != Rgb{1, 1, 1})
        for (Rgb* part : {&c.direct, &c.indirect, &c.caustic, &c.specular}) *part *= absorbed;
    return c;
}

Components Shader::shade_hit(const Ray& ray, const Hit& hit, const SurfacePoint& surface, int depth, Emission emission,
                             const PixelSample& pixel, const LightStrata& strata, Pcg32& rng) const {
    Components c;
    // An emitter seen by the camera is direct light (as bright as it is at this frame); seen
    // through a mirror the caller files it under specular.
    const Rgb Le = m_context.frame.emission[size_t(surface.object)];
    if (emission == Emission::counted && !pixel.skip_direct && !is_black(Le)) {
        c.direct += emitted_radiance_at(m_context, surface, -ray.d);
        if (pixel.direct_log) pixel.direct_log->spoil();
    }
    const SurfacePoint sp = face_towards(surface, ray.d);
    const SurfaceBsdf surface_bsdf = bsdf_at(m_context, sp);
    const Bsdf& bsdf = *surface_bsdf;
    const OrthonormalBasis basis = OrthonormalBasis::from_normal(sp.nm);
    const Vec3 wo = basis.to_local(-ray.d);
    if (bsdf.is_diffuse()) {
        if (pixel.direct_only) {
            c.direct += direct_light(sp, basis, bsdf, wo, strata, pixel);
            return c;
        }
        PixelSample at = pixel;
        // Within a pixel the camera's rays spread over about one footprint; at grazing angles
        // over more, hence the factor 2.
        at.reach = 2 * m_context.frame.camera.pixel_footprint(hit.t);
        if (depth > 0) at.memo = at.caustic_memo = nullptr;
        if (depth == 0 && pixel.recorder) pixel.recorder->add_surface_ray(pixel.pixel_index);
        shade_diffuse(sp, basis, bsdf, wo, depth, at, strata, c);
        if (const std::unique_ptr<Bsdf> coat = bsdf.non_diffuse_part()) {
            if (pixel.recorder) pixel.recorder->add_flags(pixel.pixel_index, PixelRecorder::coat);
            c.specular = trace_coat(*coat, surface, ray, rng);
        }
        return c;
    }
    if (pixel.direct_log) pixel.direct_log->spoil();  // kept: diffuse points only
    // Glossy surfaces take direct light by light sampling; the sampled bounce then carries only
    // indirect light (emission is not counted twice). Mirrors and glass see emitters directly.
    // The BSDF is evaluated in the frame of the surface's own normals, as sample_bounce samples
    // it: rough glass tells inside from outside by them (the reflective BSDFs are two-sided).
    // So do the lights' images in flat mirrors.
    if (!bsdf.is_delta() && !pixel.skip_direct) {
        const OrthonormalBasis own = OrthonormalBasis::from_normal(surface.nm);
        c.direct += direct_light(sp, own, bsdf, own.to_local(-ray.d), strata, pixel);
        c.direct += light_in_mirrors(sp, own, bsdf, own.to_local(-ray.d), strata, pixel);
    }
    if (depth >= m_settings.max_specular_depth || pixel.direct_only) return c;
    // A flat mirror reached by a glossy bounce reflects light that the glossy point sampled.
    const Emission delta_emission = emission == Emission::sampled && is_flat_mirror(surface.object)
                                        ? Emission::sampled_in_mirror
                                        : Emission::counted;
    // What the bounce sees keeps this camera ray's light strata: each camera ray still reaches
    // at most one diffuse point along each branch.
    const auto follow = [&](const Bounce& bounce, float weight, BranchShare share) {
        PixelSample branch = pixel;
        branch.share = std::max(pixel.share, share);
        const Emission next = bounce.sample.is_delta ? delta_emission : Emission::sampled;
        c.specular += bounce.sample.weight * weight * shade(bounce.ray, depth + 1, next, branch, strata, rng).sum();
    };
    const float u_lobe = rng.next_float();
    const Vec2 u = rng.next_vec2();
    if (bsdf.is_delta() && depth < max_split_depth) {
        // Glass both reflects and refracts: near the camera both are followed, each weighted by
        // the probability sample() gives it (the first lobe for u_lobe 0, the last just below
        // 1), rather than one chosen at random, whose noise would show through every glass
        // object. A single lobe (a mirror, total internal reflection) is followed once.
        const auto share_of = [](const Bounce& lobe) {
            return lobe.sample.pdf < 0.5f ? BranchShare::minor : BranchShare::whole;
        };
        const std::optional<Bounce> first = sample_bounce(bsdf, surface, ray.d, u, 0.0f, TransportMode::radiance);
        if (first && first->sample.pdf < 1) {
            follow(*first, first->sample.pdf, share_of(*first));
            const std::optional<Bounce> last =
                sample_bounce(bsdf, surface, ray.d, u, 0x1.fffffep-1f, TransportMode::radiance);
            if (last) follow(*last, last->sample.pdf, share_of(*last));
        } else if (first) {
            follow(*first, 1, BranchShare::whole);
        }
        return c;
    }
    // A glossy surface the camera sees (rough glass above all) is followed along several
    // bounces, each with numbers of its own: through a frosted pane one bounce's noise shows as
    // grain, a lamp seen through it now and then as a speck (docs/notes/truth-glossy-surfaces.md).
    const int bounces = depth == 0 ? glossy_camera_bounces : 1;
    for (int k = 0; k < bounces; ++k) {
        const std::optional<Bounce> bounce =
            k == 0 ? sample_bounce(bsdf, surface, ray.d, u, u_lobe, TransportMode::radiance)
                   : sample_bounce(bsdf, surface, ray.d, rng.next_vec2(), rng.next_float(), TransportMode::radiance);
        if (bounce) follow(*bounce, 1.0f / float(bounces), bounces > 1 ? BranchShare::glossy : BranchShare::whole);
    }
    return c;
}

}  // namespace

const PixelMemo::Values* PixelMemo::find(const SurfacePoint& sp, Vec3 n, float reach) const {
    constexpr float min_cos_normals = 0.99f;  // about 8 degrees
    for (int i = 0; i < m_count; ++i) {
        const Entry& e = m_entries[size_t(i)];
        if (e.object == sp.object && dot(e.n, n) > min_cos_normals && length2(e.p - sp.p) <= reach * reach) {
            m_last = i;
            return &e.values;
        }
    }
    m_last = -1;
    return nullptr;
}

void PixelMemo::add(const SurfacePoint& sp, Vec3 n, const Values& values) {
    m_last = m_count < capacity ? m_count : -1;
    if (m_count < capacity) m_entries[size_t(m_count++)] = {sp.object, sp.p, n, values};
}

ShadedFrame shade_frame(const FrameContext& context, const ShadingSettings& settings, const PhotonMap& caustic,
                        const IndirectIrradiance& indirect, const ReflectedRadiance& reflected, Visibility visibility,
                        PixelSource* source, int extra_layers, unsigned grey_extras) {
    SL_CHECK(extra_layers >= 0 && extra_layers <= max_extra_layers);
    const Camera& camera = context.frame.camera;
    ShadedFrame out;
    for (Image* image : {&out.beauty, &out.direct, &out.indirect, &out.caustic, &out.specular})
        *image = Image::unfilled(camera.width, camera.height);  // every pixel written below
    const auto is_grey = [grey_extras](int e) { return (grey_extras >> e & 1) != 0; };
    for (int e = 0; e < extra_layers; ++e)
        if (is_grey(e))
            out.grey_extra[size_t(e)] = GreyImage::unfilled(camera.width, camera.height);
        else
            out.extra[size_t(e)] = Image::unfilled(camera.width, camera.height);
    if (camera.transparent_background) out.alpha = Image::unfilled(camera.width, camera.height);
    const int n = settings.samples_per_pixel;
    const Shader shader(context, settings, caustic, indirect, reflected, visibility, extra_layers);
    PixelRecorder* const recorder = source ? source->recorder() : nullptr;
    const float inv_n = 1.0f / float(n);
    parallel_for_tiles(camera.width, camera.height, shading_tile_size, [&](int x0, int y0, int x1, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                const size_t i = size_t(y) * size_t(camera.width) + size_t(x);
                PixelSums sum;
                const PixelSource::Shading shading = source ? source->begin(x, y, i, sum) : PixelSource::Shading::all;
                if (shading != PixelSource::Shading::none) {
                    // The same numbers for a pixel in every frame: where nothing changes, nothing
                    // flickers (paper §4; bit-identical static regions).
                    Pcg32 constants = pixel_stream(camera, x, y, PixelStream::constants);
                    const Vec2 shift = constants.next_vec2();
                    const LightStrata strata{0, uint32_t(n * settings.direct_samples), constants.next_vec2()};
                    // Camera ray s takes the light strata of ray order(s), not of s: both run over the
                    // pixel in the same order, and the light chosen from a stratum would otherwise
                    // follow the ray's place in the pixel (a bias at the edges of what one light lights).
                    const uint32_t order_seed = constants.next_u32();
                    PixelMemo memo, caustic_memo;
                    PixelSample pixel{x, y, 0, n, &memo, &caustic_memo};
                    pixel.recorder = recorder;
                    pixel.pixel_index = i;
                    pixel.skip_direct = shading == PixelSource::Shading::all_but_direct;
                    pixel.direct_only = shading == PixelSource::Shading::direct_only;
                    if (pixel.direct_only) {
                        pixel.direct_log = source->direct_light_log(x, y, i);
                        // Its split of the shadow rays' queries is the whole scene's.
                        SL_CHECK(!pixel.direct_log || visibility == Visibility::everything);
                    }
                    PixelSums shaded;
                    for (int s = 0; s < n; ++s) {
                        const Vec2 jitter = stratified_2d(uint32_t(s), uint32_t(n), shift);
                        const Ray ray = camera.generate_ray(float(x) + jitter.x, float(y) + jitter.y);
                        const LightStrata ray_strata{
                            permuted_index(uint32_t(s), uint32_t(n), order_seed) * uint32_t(settings.direct_samples),
                            strata.count, strata.shift};
                        Pcg32 path = pixel_stream(camera, x, y, PixelStream::path, s);
                        pixel.sample = s;
                        const Components c = shader.shade(ray, 0, Emission::counted, pixel, ray_strata, path);
                        shaded.covered += c.covered;  // a ray whose light is dropped still met its surface
                        if (!is_finite(c.sum())) continue;
                        shaded.direct += c.direct, shaded.indirect += c.indirect, shaded.caustic += c.caustic,
                            shaded.specular += c.specular;
                        for (int e = 0; e < max_extra_layers; ++e) shaded.extra[size_t(e)] += c.extra[size_t(e)];
                    }
                    // Where the source gave the rest, a ray's direct light counts where it is
                    // finite: a ray whose other terms were not would have been dropped whole, but
                    // those terms are never infinite or NaN (a defect, output/frame_layers.h).
                    if (pixel.direct_only)
                        sum.direct = shaded.direct;
                    else
                        sum = shaded;
                    if (source) source->finish(i, sum);
                }
                out.direct.at(x, y) = sum.direct * inv_n;
                out.indirect.at(x, y) = sum.indirect * inv_n;
                out.caustic.at(x, y) = sum.caustic * inv_n;
                out.specular.at(x, y) = sum.specular * inv_n;
                out.beauty.at(x, y) = sum.sum() * inv_n;
                if (out.alpha) out.alpha->at(x, y) = Rgb{1, 1, 1} * (sum.covered * inv_n);
                for (int e = 0; e < extra_layers; ++e)
                    if (is_grey(e))
                        out.grey_extra[size_t(e)].at(x, y) = sum.extra[size_t(e)].r * inv_n;
                    else
                        out.extra[size_t(e)].at(x, y) = sum.extra[size_t(e)] * inv_n;
            }
    });
    out.caustic_cpu_s = shader.caustic_cpu_s();
    return out;
}

void validate(const ShadingSettings& settings, const std::string& where) {
    check_setting_range(where + "/samples_per_pixel", settings.samples_per_pixel, 1, 1 << 20);
    check_setting_range(where + "/direct_samples", settings.direct_samples, 1, 4096);
    check_setting_range(where + "/max_specular_depth", settings.max_specular_depth, 0, 10000);
    validate(settings.caustic_estimate, where + "/caustic_estimate");
}

}  // namespace steadylight
