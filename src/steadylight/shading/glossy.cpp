// Glossy reflection from a rough surface: the GGX (Trowbridge-Reitz) microfacet model with the
// separable Smith shadowing term and Schlick's Fresnel with the reflectance as its normal-
// incidence colour (Walter et al. 2007). Half vectors are sampled in proportion to D(h) cos(h).
#include <cmath>

#include "steadylight/shading/bsdf.h"

namespace steadylight {
namespace {

class Glossy final : public Bsdf {
public:
    Glossy(Rgb reflectance, float roughness) : m_reflectance(reflectance), m_alpha(roughness * roughness) {}

    Rgb eval(Vec3 wo, Vec3 wi) const override {
        if (wo.z * wi.z <= 0) return {};
        // Work on the upper side: the BSDF is two-sided.
        if (wo.z < 0) wo.z = -wo.z, wi.z = -wi.z;
        const Vec3 h = normalize(wo + wi);
        const float g = smith_g1(wo) * smith_g1(wi);
        return schlick(dot(wo, h)) * (ggx_d(h.z) * g / (4 * wo.z * wi.z));
    }

    float pdf(Vec3 wo, Vec3 wi) const override {
        if (wo.z * wi.z <= 0) return 0;
        if (wo.z < 0) wo.z = -wo.z, wi.z = -wi.z;
        const Vec3 h = normalize(wo + wi);
        return ggx_d(h.z) * h.z / (4 * dot(wo, h));
    }

    std::optional<BsdfSample> sample(Vec3 wo, Vec2 u, float, TransportMode) const override {
        if (wo.z == 0) return std::nullopt;
        const float side = wo.z > 0 ? 1.0f : -1.0f;
        const Vec3 wo_up{wo.x, wo.y, wo.z * side};
        // Invert the CDF of D(h) cos(h): tan^2(theta) = alpha^2 u / (1 - u).
        const float tan2 = m_alpha * m_alpha * u.x / (1 - u.x);
        const float cos_theta = 1 / std::sqrt(1 + tan2);
        const float sin_theta = std::sqrt(std::max(0.0f, 1 - cos_theta * cos_theta));
        const float phi = 2 * pi * u.y;
        const Vec3 h{sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
        const Vec3 wi_up = reflect(wo_up, h);
        if (wi_up.z <= 0) return std::nullopt;
        const Vec3 wi{wi_up.x, wi_up.y, wi_up.z * side};
        const float p = pdf(wo, wi);
        if (!(p > 0)) return std::nullopt;
        return BsdfSample{wi, eval(wo, wi) * (std::abs(wi.z) / p), p, false};
    }

private:
    float ggx_d(float cos_h) const {
        const float a2 = m_alpha * m_alpha;
        const float d = cos_h * cos_h * (a2 - 1) + 1;
        return a2 / (pi * d * d);
    }

    float smith_g1(Vec3 w) const {
        const float cos2 = w.z * w.z;
        const float tan2 = std::max(0.0f, 1 - cos2) / cos2;
        return 2 / (1 + std::sqrt(1 + m_alpha * m_alpha * tan2));
    }

    Rgb schlick(float cos_theta) const {
        const float m = std::pow(1 - std::clamp(cos_theta, 0.0f, 1.0f), 5.0f);
        return m_reflectance + (Rgb{1, 1, 1} - m_reflectance) * m;
    }

    Rgb m_reflectance;
    float m_alpha;
};

}  // namespace

std::unique_ptr<Bsdf> make_glossy(Rgb reflectance, float roughness) {
    return std::make_unique<Glossy>(reflectance, roughness);
}

}  // namespace steadylight
