#include "steadylight/photons/photon_tracer.h"

#include <vector>

#include "steadylight/base/halton.h"
#include "steadylight/base/parallel.h"
#include "steadylight/base/rng.h"
#include "steadylight/shading/surface_point.h"

namespace steadylight {
namespace {

enum class MapKind { global, caustic };

/// The random numbers of one photon path: Halton dimensions while they last, then a stream
/// hashed from the photon index (deep bounces matter little and are rare).
class PhotonSampler {
public:
    explicit PhotonSampler(uint64_t index) : m_index(index), m_rng(hash_ids(index, 0x9407)) {}
    float next() { return m_dimension < halton_dimensions ? halton(m_dimension++, m_index) : m_rng.next_float(); }
    Vec2 next_vec2() {
        const float x = next();
        return {x, next()};
    }

private:
    uint64_t m_index;
    int m_dimension = 0;
    Pcg32 m_rng;
};

/// Follows photon `index` from its light until it is absorbed, storing it where `kind` wants.
void trace_photon(const FrameContext& context, uint64_t index, float scale, MapKind kind,
                  const PhotonSettings& settings, Visibility visibility, std::vector<Photon>& out) {
    PhotonSampler sampler(index);
    const float u_select = sampler.next();
    const Vec2 u_position = sampler.next_vec2();
    const std::optional<EmissionSample> emission = context.lights.sample_emission(u_select, u_position, sampler.next_vec2());
    if (!emission || is_black(emission->power)) return;
    Rgb power = emission->power * scale;
    // Photons from area lights leave the surface; point lights have no surface to leave.
    Ray ray = length2(emission->n) > 0 ? spawn_ray(emission->p, emission->n, emission->d) : Ray{emission->p, emission->d};
    bool specular_path = false;  // every bounce so far was specular or glossy
    for (int bounce = 0; bounce < settings.max_bounces; ++bounce) {
        const std::optional<Hit> hit = context.tracer.intersect(ray, visibility);
        if (!hit) return;
        const SurfacePoint sp = make_surface_point(context.scene, context.frame, ray, *hit);
        const Bsdf& bsdf = context.bsdf_of(sp.object);
        const Vec3 arrival_n = dot(sp.ng, ray.d) < 0 ? sp.ng : -sp.ng;

        // Store at diffuse surfaces: all hits for the global map, L S+ D ends for the caustic one.
        if (bsdf.is_diffuse()) {
            if (kind == MapKind::global || specular_path)
                out.push_back({sp.p, arrival_n, -ray.d, power, uint16_t(bounce)});
            if (kind == MapKind::caustic) return;
        }

        // Scatter, or be absorbed: survive with the probability of the scattered power.
        const Frame frame = Frame::from_normal(sp.ns);
        const float u_lobe = sampler.next(), u_survive = sampler.next();
        const std::optional<BsdfSample> bs = bsdf.sample(frame.to_local(-ray.d), sampler.next_vec2(), u_lobe,
                                                         TransportMode::importance);
        if (!bs) return;
        const float survive = std::min(1.0f, max_component(bs->weight));
        if (!(u_survive < survive)) return;
        power *= bs->weight / survive;
        specular_path = (bounce == 0 || specular_path) && !bsdf.is_diffuse();
        ray = spawn_ray(sp.p, sp.ng, frame.to_world(bs->wi));
    }
}

PhotonMap trace_map(const FrameContext& context, long count, MapKind kind, const PhotonSettings& settings,
                    Visibility visibility) {
    if (count <= 0 || context.lights.empty()) return {};
    // Chunks store into their own vectors, joined in chunk order: the same map for any threads.
    constexpr long chunk = 4096;
    std::vector<std::vector<Photon>> chunks(size_t((count + chunk - 1) / chunk));
    // The caustic map uses other points of the sequence than the global one.
    const uint64_t first = kind == MapKind::global ? 0 : uint64_t(1) << 32;
    const float scale = 1.0f / float(count);
    parallel_for_chunks(count, chunk, [&](long begin, long end) {
        std::vector<Photon>& out = chunks[size_t(begin / chunk)];
        for (long i = begin; i < end; ++i) trace_photon(context, first + uint64_t(i), scale, kind, settings, visibility, out);
    });
    std::vector<Photon> photons;
    for (const auto& c : chunks) photons.insert(photons.end(), c.begin(), c.end());
    return PhotonMap(std::move(photons), count);
}

}  // namespace

TracedPhotons trace_photons(const FrameContext& context, const PhotonSettings& settings, Visibility visibility) {
    return {trace_map(context, settings.global_photons, MapKind::global, settings, visibility),
            trace_map(context, settings.caustic_photons, MapKind::caustic, settings, visibility)};
}

}  // namespace steadylight
