// A rough dielectric boundary (frosted glass): GGX microfacets, each a smooth dielectric that
// reflects or refracts (Walter, Marschner, Li & Torrance 2007, "Microfacet Models for Refraction
// through Rough Surfaces", eqs. 20-21), sampled by the normals visible from wo (Heitz 2018) with
// reflection or refraction chosen by that microfacet's Fresnel, as pbrt-v4's DielectricBxDF does.
// The normal points outside; `ior` is inside over outside.
//
// Light that bounces between microfacets, which single scattering loses (4% on average at
// roughness 0.3, a third at 1), is put back by a multiple-scattering lobe in the manner of Kulla
// and Conty (2017): seen from a side s, the single-scattering albedo (reflection plus
// transmission, energy) is E_s(mu), tabulated per index of refraction over cos theta and
// roughness from both sides, and the lobe adds
//   reflection   k_r,s (1 - E_s(mu_o)) (1 - E_s(mu_i)) / (pi (1 - E_s,avg))
//   transmission k_t,s (1 - E_s(mu_o)) (1 - E_s'(mu_i)) / (pi (1 - E_s',avg))   (s' the other side)
// with k_r,s + k_t,s = 1, so that the white furnace holds from either side at every angle. The
// split follows the smooth boundary's mean Fresnel seen from outside (k_t,outside = 1 - F_avg),
// and the inside's is what generalised reciprocity then asks (f / eta_o^2 = f^T / eta_i^2):
// k_t,inside = k_t,outside (1 - E_outside,avg) / (ior^2 (1 - E_inside,avg)), less than it, as
// total internal reflection keeps more light inside. docs/materials.md "Glass".
#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>

#include "steadylight/base/rng.h"
#include "steadylight/base/sampling.h"
#include "steadylight/shading/albedo_table.h"
#include "steadylight/shading/bsdf.h"
#include "steadylight/shading/microfacet.h"

namespace steadylight {
namespace {

float sqr(float x) { return x * x; }

/// The direction refracted through a microfacet of normal `h` (either orientation), or nothing
/// under total internal reflection; `ior` is inside over outside.
std::optional<Vec3> refract_through(Vec3 wo, Vec3 h, float ior) {
    const float cos_o = dot(wo, h);
    const float eta = cos_o > 0 ? ior : 1 / ior;  // eta_t / eta_i across the microfacet
    const Vec3 n = cos_o > 0 ? h : -h;
    const float cos_i = std::abs(cos_o);
    const float sin2_t = (1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1) return std::nullopt;
    return -wo / eta + n * (cos_i / eta - std::sqrt(1 - sin2_t));
}

/// The single-scattering albedo tables of glass of one index, and the smooth boundary's mean
/// Fresnel reflectance seen from outside.
struct GlassAlbedo {
    AlbedoTable table;  // channels: seen from outside, from inside
    float fresnel_average_outside;
};

/// Single scattering's energy albedo seen from outside (wo.z = mu) and inside (wo.z = -mu):
/// over the normals visible from wo, the reflected and the refracted weight G2 / G1(wo), each
/// times its share of the microfacet's Fresnel (both branches, no lobe sampled). Jittered
/// strata, finer in the radius of the visible-normal disc: total internal reflection cuts that
/// disc along a curve, which strata centred on a grid would alias (1% too much at normal
/// incidence from inside, roughness 0.3).
AlbedoTable::Channels single_scattering_albedo(float ior, float mu, float roughness) {
    constexpr int radial = 64, angular = 32;
    const Ggx ggx(roughness * roughness);
    Pcg32 rng(std::bit_cast<uint32_t>(mu), std::bit_cast<uint32_t>(roughness));
    AlbedoTable::Channels albedo{};
    for (int side = 0; side < 2; ++side) {
        const float z = side == 0 ? mu : -mu;
        const Vec3 wo{std::sqrt(std::max(0.0f, 1 - mu * mu)), 0, z};
        double sum = 0;
        for (int a = 0; a < radial; ++a)
            for (int b = 0; b < angular; ++b) {
                const Vec2 u{(float(a) + rng.next_float()) / radial, (float(b) + rng.next_float()) / angular};
                const Vec3 h = ggx.sample_visible_normal(z > 0 ? wo : -wo, u);
                const float reflectance = fresnel_dielectric(dot(wo, h), ior);
                const Vec3 reflected = reflect(wo, h);
                if (reflected.z * z > 0) sum += reflectance * ggx.g2(wo, reflected) / ggx.g1(wo);
                const std::optional<Vec3> refracted = refract_through(wo, h, ior);
                if (refracted && refracted->z * z < 0) sum += (1 - reflectance) * ggx.g2(wo, *refracted) / ggx.g1(wo);
            }
        albedo[size_t(side)] = float(sum / (radial * angular));
    }
    return albedo;
}

GlassAlbedo make_glass_albedo(float ior) {
    constexpr int steps = 1024;
    double fresnel = 0;
    for (int k = 0; k < steps; ++k) {
        const float mu = (float(k) + 0.5f) / steps;
        fresnel += 2.0 * fresnel_dielectric(mu, ior) * mu / steps;
    }
    return {AlbedoTable(32, 32, min_pbr_roughness,
                        [ior](float mu, float roughness) { return single_scattering_albedo(ior, mu, roughness); }),
            float(fresnel)};
}

/// The tables for `ior`, made at its first use (a few tenths of a second) and kept.
const GlassAlbedo& glass_albedo(float ior) {
    static std::mutex mutex;
    static std::map<float, std::unique_ptr<GlassAlbedo>> tables;
    thread_local std::pair<float, const GlassAlbedo*> last{0.0f, nullptr};
    if (last.second && last.first == ior) return *last.second;
    const std::lock_guard lock(mutex);
    std::unique_ptr<GlassAlbedo>& entry = tables[ior];
    if (!entry) entry = std::make_unique<GlassAlbedo>(make_glass_albedo(ior));
    last = {ior, entry.get()};
    return *entry;
}

class RoughDielectric final : public Bsdf {
public:
    RoughDielectric(float ior, float roughness, Rgb transmittance)
        : m_ior(ior),
          m_roughness(roughness),
          m_ggx(roughness * roughness),
          m_transmittance(transmittance),
          m_albedo(glass_albedo(ior)) {
        const AlbedoTable::Channels average = m_albedo.table.average(roughness);
        m_one_minus_average = {std::max(1 - average[0], 1e-6f), std::max(1 - average[1], 1e-6f)};
        m_transmitted_share[0] = 1 - m_albedo.fresnel_average_outside;
        m_transmitted_share[1] = m_transmitted_share[0] * m_one_minus_average[0] / (sqr(ior) * m_one_minus_average[1]);
        if (m_transmitted_share[1] > 1) {  // an index below 1: the outside is the denser side
            m_transmitted_share[0] /= m_transmitted_share[1];
            m_transmitted_share[1] = 1;
        }
    }

    /// f for radiance (what light sampling needs); sample() gives importance too.
    Rgb eval(Vec3 wo, Vec3 wi) const override { return f(wo, wi, TransportMode::radiance); }

    float pdf(Vec3 wo, Vec3 wi) const override {
        if (wo.z == 0 || wi.z == 0) return 0;
        const float multiple = multiple_scattering_probability(wo);
        const bool reflect = wo.z * wi.z > 0;
        const float share = reflect ? 1 - transmitted_share(wo) : transmitted_share(wo);
        return (1 - multiple) * single_scattering_pdf(wo, wi) + multiple * share * std::abs(wi.z) * inv_pi;
    }

    std::optional<BsdfSample> sample(Vec3 wo, Vec2 u, float u_lobe, TransportMode mode) const override {
        if (wo.z == 0) return std::nullopt;
        const float multiple = multiple_scattering_probability(wo);
        Vec3 wi;
        if (u_lobe < multiple) {
            // The multiple-scattering lobe: a cosine-distributed direction on the side it chose.
            const bool transmit = u_lobe / multiple >= 1 - transmitted_share(wo);
            wi = sample_cosine_hemisphere(u);
            if ((wo.z > 0) == transmit) wi.z = -wi.z;
        } else {
            // Normals point outside: from inside the visible microfacets are those -wo sees.
            const Vec3 h = m_ggx.sample_visible_normal(wo.z > 0 ? wo : -wo, u);
            const float reflectance = fresnel_dielectric(dot(wo, h), m_ior);
            if ((u_lobe - multiple) / (1 - multiple) < reflectance) {
                wi = reflect(wo, h);
                if (wi.z * wo.z <= 0) return std::nullopt;
            } else {
                const std::optional<Vec3> refracted = refract_through(wo, h, m_ior);
                if (!refracted || refracted->z * wo.z >= 0) return std::nullopt;
                wi = *refracted;
            }
        }
        const float p = pdf(wo, wi);
        if (!(p > 0)) return std::nullopt;
        return BsdfSample{wi, f(wo, wi, mode) * (std::abs(wi.z) / p), p, false};
    }

private:
    struct HalfVector {
        Vec3 h;      // the microfacet normal, on the outside (z > 0)
        float etap;  // eta of wi's side over wo's side (1 for reflection)
        bool reflect;
    };

    /// 0 for a direction outside, 1 inside: the albedo table's channel.
    static size_t side(Vec3 w) { return w.z > 0 ? 0 : 1; }

    /// Single scattering's albedo seen from `w`, on its own side.
    float single_scattering_albedo(Vec3 w) const {
        return std::clamp(m_albedo.table.at(std::abs(w.z), m_roughness)[side(w)], 0.0f, 1.0f);
    }
    /// The chance that sample() draws the multiple-scattering lobe: its share of the albedo.
    float multiple_scattering_probability(Vec3 wo) const { return 1 - single_scattering_albedo(wo); }
    float transmitted_share(Vec3 wo) const { return m_transmitted_share[side(wo)]; }

    /// The generalised half vector of wo and wi (Walter et al. eq. 16), or nothing when the pair
    /// cannot be connected by a microfacet that faces both of them.
    std::optional<HalfVector> half_vector(Vec3 wo, Vec3 wi) const {
        if (wo.z == 0 || wi.z == 0) return std::nullopt;
        const bool reflect = wo.z * wi.z > 0;
        const float etap = reflect ? 1 : wo.z > 0 ? m_ior : 1 / m_ior;
        Vec3 h = wi * etap + wo;
        if (!(length2(h) > 0)) return std::nullopt;
        h = normalize(h);
        if (h.z < 0) h = -h;
        if (dot(h, wi) * wi.z <= 0 || dot(h, wo) * wo.z <= 0) return std::nullopt;  // back-facing microfacet
        return HalfVector{h, etap, reflect};
    }

    float single_scattering_pdf(Vec3 wo, Vec3 wi) const {
        const std::optional<HalfVector> hv = half_vector(wo, wi);
        if (!hv) return 0;
        const Vec3 h = hv->h;
        const float reflectance = fresnel_dielectric(dot(wo, h), m_ior);
        // The density of the visible normal h seen from wo (or from -wo inside).
        const float visible = m_ggx.g1(wo) * m_ggx.d(h) * std::abs(dot(wo, h)) / std::abs(wo.z);
        if (hv->reflect) return visible / (4 * std::abs(dot(wo, h))) * reflectance;
        const float denom = sqr(dot(wi, h) + dot(wo, h) / hv->etap);
        return visible * std::abs(dot(wi, h)) / denom * (1 - reflectance);
    }

    /// Single scattering's f for energy (importance): reflection, or transmission before its tint.
    float single_scattering_f(Vec3 wo, Vec3 wi) const {
        const std::optional<HalfVector> hv = half_vector(wo, wi);
        if (!hv) return 0;
        const Vec3 h = hv->h;
        const float reflectance = fresnel_dielectric(dot(wo, h), m_ior);
        const float dg = m_ggx.d(h) * m_ggx.g2(wo, wi);
        if (hv->reflect) return dg * reflectance / std::abs(4 * wo.z * wi.z);
        const float denom = sqr(dot(wi, h) + dot(wo, h) / hv->etap) * wi.z * wo.z;
        return dg * (1 - reflectance) * std::abs(dot(wi, h) * dot(wo, h) / denom);
    }

    /// The multiple-scattering lobe's f for energy (the header's formula).
    float multiple_scattering_f(Vec3 wo, Vec3 wi) const {
        const bool reflect = wo.z * wi.z > 0;
        const float share = reflect ? 1 - transmitted_share(wo) : transmitted_share(wo);
        return share * (1 - single_scattering_albedo(wo)) * (1 - single_scattering_albedo(wi)) /
               (pi * m_one_minus_average[side(wi)]);
    }

    Rgb f(Vec3 wo, Vec3 wi, TransportMode mode) const {
        if (wo.z == 0 || wi.z == 0) return {};
        const float energy = single_scattering_f(wo, wi) + multiple_scattering_f(wo, wi);
        if (wo.z * wi.z > 0) return {energy, energy, energy};
        // Radiance is compressed into the denser medium's smaller solid angle (Veach 1997, §5.2).
        const float etap = wo.z > 0 ? m_ior : 1 / m_ior;
        return m_transmittance * (mode == TransportMode::radiance ? energy / sqr(etap) : energy);
    }

    float m_ior, m_roughness;
    Ggx m_ggx;
    Rgb m_transmittance;
    const GlassAlbedo& m_albedo;
    std::array<float, 2> m_one_minus_average{};  // 1 - E_avg seen from outside, from inside
    std::array<float, 2> m_transmitted_share{};  // k_t seen from outside, from inside
};

}  // namespace

std::unique_ptr<Bsdf> make_rough_dielectric(float ior, float roughness, Rgb transmittance) {
    return std::make_unique<RoughDielectric>(ior, std::clamp(roughness, min_pbr_roughness, 1.0f), transmittance);
}

}  // namespace steadylight
