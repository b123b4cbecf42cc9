// A rough dielectric boundary (frosted glass): GGX microfacets, each a smooth dielectric that
// reflects or refracts (Walter, Marschner, Li & Torrance 2007, "Microfacet Models for Refraction
// through Rough Surfaces", eqs. 20-21), sampled by the normals visible from wo (Heitz 2018) with
// reflection or refraction chosen by that microfacet's Fresnel, as pbrt-v4's DielectricBxDF does.
// Single scattering: light that bounces between microfacets is lost (4% on average at roughness
// 0.3, a third at 1: docs/materials.md "Glass"). The normal points outside; `ior` is inside over
// outside.
#include <algorithm>
#include <cmath>

#include "steadylight/shading/bsdf.h"
#include "steadylight/shading/microfacet.h"

namespace steadylight {
namespace {

class RoughDielectric final : public Bsdf {
public:
    RoughDielectric(float ior, float roughness, Rgb transmittance)
        : m_ior(ior), m_ggx(roughness * roughness), m_transmittance(transmittance) {}

    /// f for radiance (what light sampling needs); sample() gives importance too.
    Rgb eval(Vec3 wo, Vec3 wi) const override { return f(wo, wi, TransportMode::radiance); }

    float pdf(Vec3 wo, Vec3 wi) const override {
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

    std::optional<BsdfSample> sample(Vec3 wo, Vec2 u, float u_lobe, TransportMode mode) const override {
        if (wo.z == 0) return std::nullopt;
        // Normals point outside: from inside the visible microfacets are those -wo sees.
        const Vec3 h = m_ggx.sample_visible_normal(wo.z > 0 ? wo : -wo, u);
        const float cos_o = dot(wo, h);
        const float reflectance = fresnel_dielectric(cos_o, m_ior);
        Vec3 wi;
        if (u_lobe < reflectance) {
            wi = reflect(wo, h);
            if (wi.z * wo.z <= 0) return std::nullopt;
        } else {
            // Refract through the microfacet: eta = eta_t / eta_i across it.
            const float eta = cos_o > 0 ? m_ior : 1 / m_ior;
            const Vec3 n = cos_o > 0 ? h : -h;
            const float cos_i = std::abs(cos_o);
            const float sin2_t = (1 - cos_i * cos_i) / (eta * eta);
            if (sin2_t >= 1) return std::nullopt;
            wi = -wo / eta + n * (cos_i / eta - std::sqrt(1 - sin2_t));
            if (wi.z * wo.z >= 0) return std::nullopt;
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

    static float sqr(float x) { return x * x; }

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

    Rgb f(Vec3 wo, Vec3 wi, TransportMode mode) const {
        const std::optional<HalfVector> hv = half_vector(wo, wi);
        if (!hv) return {};
        const Vec3 h = hv->h;
        const float reflectance = fresnel_dielectric(dot(wo, h), m_ior);
        const float dg = m_ggx.d(h) * m_ggx.g2(wo, wi);
        if (hv->reflect) {
            const float r = dg * reflectance / std::abs(4 * wo.z * wi.z);
            return {r, r, r};
        }
        const float denom = sqr(dot(wi, h) + dot(wo, h) / hv->etap) * wi.z * wo.z;
        float t = dg * (1 - reflectance) * std::abs(dot(wi, h) * dot(wo, h) / denom);
        // Radiance is compressed into the denser medium's smaller solid angle (Veach 1997, §5.2).
        if (mode == TransportMode::radiance) t /= sqr(hv->etap);
        return m_transmittance * t;
    }

    float m_ior;
    Ggx m_ggx;
    Rgb m_transmittance;
};

}  // namespace

std::unique_ptr<Bsdf> make_rough_dielectric(float ior, float roughness, Rgb transmittance) {
    return std::make_unique<RoughDielectric>(ior, std::clamp(roughness, min_pbr_roughness, 1.0f), transmittance);
}

}  // namespace steadylight
