// glTF's metallic-roughness material (glTF 2.0 Appendix B) as one BSDF: a mix, by `metallic`,
// of a GGX conductor whose Schlick Fresnel starts at the base colour, and a dielectric: a GGX
// coat (Schlick Fresnel from the ior, scaled as KHR_materials_specular says) over a Lambertian
// base. Both GGX lobes get Kulla and Conty's multiple-scattering lobe, and the base sees only
// the energy the coat leaves it: f_base = base / pi (1 - E_coat(wo)) (1 - E_coat(wi)) /
// (1 - E_coat_avg), which is reciprocal and makes a white material reflect exactly all the
// light at every angle and roughness (docs/materials.md). Sampling mixes visible-normal GGX
// samples and cosine samples in proportion to the single-scattering and the broad lobes' albedos.
#include <cmath>

#include "steadylight/base/sampling.h"
#include "steadylight/shading/bsdf.h"
#include "steadylight/shading/microfacet.h"

namespace steadylight {
namespace {

/// Kulla-Conty's Fresnel factor for the multiple-scattering lobe: the energy that leaves after
/// bouncing between microfacets, each bounce keeping F_avg of it.
float ms_fresnel(float f_avg, float e_avg) { return f_avg * f_avg * e_avg / (1 - f_avg * (1 - e_avg)); }

class Pbr final : public Bsdf {
public:
    Pbr(const PbrParams& p, bool with_base) : m_p(p), m_ggx(p.roughness * p.roughness), m_with_base(with_base) {
        m_avg = ggx_average_albedo(p.roughness);
        const float coat_f_avg = p.specular * (p.f0 + (1 - p.f0) / 21);
        m_coat_ms = ms_fresnel(coat_f_avg, m_avg.e);
        for (int c = 0; c < 3; ++c) {
            const float f_avg = p.base[c] + (1 - p.base[c]) / 21;
            (&m_metal_ms.r)[c] = ms_fresnel(f_avg, m_avg.e);
        }
        m_coat_avg = coat_albedo(m_avg);
    }

    bool is_diffuse() const override { return m_with_base && has_base(); }
    Rgb diffuse_reflectance(Vec3 wo) const override {
        if (!is_diffuse()) return {};
        return m_p.base * ((1 - m_p.metallic) * (1 - coat_albedo(ggx_albedo(std::abs(wo.z), m_p.roughness))));
    }
    std::unique_ptr<Bsdf> non_diffuse_part() const override { return std::make_unique<Pbr>(m_p, false); }

    Rgb eval(Vec3 wo, Vec3 wi) const override {
        if (wo.z * wi.z <= 0) return {};
        if (wo.z < 0) wo.z = -wo.z, wi.z = -wi.z;
        return eval_upper(wo, wi);
    }

    float pdf(Vec3 wo, Vec3 wi) const override {
        if (wo.z * wi.z <= 0) return 0;
        if (wo.z < 0) wo.z = -wo.z, wi.z = -wi.z;
        const float p_spec = specular_probability(wo);
        return p_spec * m_ggx.pdf_reflection(wo, wi) + (1 - p_spec) * cosine_hemisphere_pdf(wi.z);
    }

    std::optional<BsdfSample> sample(Vec3 wo, Vec2 u, float u_lobe, TransportMode) const override {
        if (wo.z == 0) return std::nullopt;
        const float side = wo.z > 0 ? 1.0f : -1.0f;
        const Vec3 wo_up{wo.x, wo.y, wo.z * side};
        const bool spec = u_lobe < specular_probability(wo_up);
        const Vec3 wi_up = spec ? reflect(wo_up, m_ggx.sample_visible_normal(wo_up, u)) : sample_cosine_hemisphere(u);
        if (wi_up.z <= 0) return std::nullopt;
        const Vec3 wi{wi_up.x, wi_up.y, wi_up.z * side};
        const float p = pdf(wo, wi);
        if (!(p > 0)) return std::nullopt;
        BsdfSample s{wi, eval_upper(wo_up, wi_up) * (wi_up.z / p), p, false};
        s.diffuse = !spec;
        return s;
    }

private:
    bool has_base() const { return m_p.metallic < 1 && max_component(m_p.base) > 0; }

    /// The coat's directional albedo, single and multiple scattering, from the GGX albedo.
    float coat_albedo(GgxAlbedo a) const {
        return m_p.specular * (m_p.f0 * a.e + (1 - m_p.f0) * a.e_schlick) + m_coat_ms * (1 - a.e);
    }

    /// The chance of sampling visible normals rather than the cosine: the single-scattering
    /// lobes' share of the albedo. The multiple-scattering lobes and the base are broad, and
    /// cosine samples find them.
    float specular_probability(Vec3 wo) const {
        const GgxAlbedo a = ggx_albedo(wo.z, m_p.roughness);
        const Rgb one{1, 1, 1};
        const float metal_single = luminance(m_p.base * a.e + (one - m_p.base) * a.e_schlick);
        const float coat_single = m_p.specular * (m_p.f0 * a.e + (1 - m_p.f0) * a.e_schlick);
        const float single = m_p.metallic * metal_single + (1 - m_p.metallic) * coat_single;
        float broad = m_p.metallic * luminance(m_metal_ms) * (1 - a.e) + (1 - m_p.metallic) * m_coat_ms * (1 - a.e);
        if (m_with_base) broad += (1 - m_p.metallic) * luminance(m_p.base) * (1 - coat_albedo(a));
        return std::clamp(single / std::max(single + broad, 1e-6f), 0.1f, 0.95f);
    }

    Rgb eval_upper(Vec3 wo, Vec3 wi) const {
        const Vec3 h = normalize(wo + wi);
        const float single = m_ggx.d(h) * m_ggx.g2(wo, wi) / (4 * wo.z * wi.z);
        const float schlick = std::pow(1 - std::clamp(dot(wo, h), 0.0f, 1.0f), 5.0f);
        const GgxAlbedo ao = ggx_albedo(wo.z, m_p.roughness), ai = ggx_albedo(wi.z, m_p.roughness);
        const float multiple = (1 - ao.e) * (1 - ai.e) / (pi * std::max(1 - m_avg.e, 1e-6f));
        Rgb f;
        if (m_p.metallic > 0) {
            const Rgb one{1, 1, 1};
            const Rgb fresnel = m_p.base + (one - m_p.base) * schlick;
            f += (fresnel * single + m_metal_ms * multiple) * m_p.metallic;
        }
        if (m_p.metallic < 1) {
            const float fresnel = m_p.specular * (m_p.f0 + (1 - m_p.f0) * schlick);
            Rgb dielectric = Rgb{1, 1, 1} * (fresnel * single + m_coat_ms * multiple);
            if (m_with_base)
                dielectric += m_p.base * (inv_pi * (1 - coat_albedo(ao)) * (1 - coat_albedo(ai)) /
                                          std::max(1 - m_coat_avg, 1e-6f));
            f += dielectric * (1 - m_p.metallic);
        }
        return f;
    }

    PbrParams m_p;
    Ggx m_ggx;
    bool m_with_base;
    GgxAlbedo m_avg;
    float m_coat_ms = 0;
    Rgb m_metal_ms;
    float m_coat_avg = 0;
};

}  // namespace

std::unique_ptr<Bsdf> make_pbr(const PbrParams& params) {
    PbrParams p = params;
    p.roughness = std::clamp(p.roughness, min_pbr_roughness, 1.0f);
    // Without a coat or metal, the pbr material is exactly Lambertian: keep it simple.
    if (p.metallic <= 0 && p.specular <= 0) return make_lambert(p.base);
    return std::make_unique<Pbr>(p, true);
}

float pbr_f0(float ior, float specular_color) {
    const float r = (ior - 1) / (ior + 1);
    return std::min(1.0f, r * r * specular_color);
}

}  // namespace steadylight
