// The GGX (Trowbridge-Reitz) microfacet distribution with the height-correlated Smith masking-
// shadowing term (Heitz 2014), sampled by its distribution of visible normals (Heitz 2018,
// "Sampling the GGX Distribution of Visible Normals"), and the tables of its directional albedo
// that Kulla and Conty's multiple-scattering compensation needs (Kulla & Conty 2017, "Revisiting
// Physically Based Shading at Imageworks"). Local frame: the normal is +z; both directions on
// the upper side.
#pragma once

#include "steadylight/base/vec.h"

namespace steadylight {

class Ggx {
public:
    explicit Ggx(float alpha) : m_alpha(alpha) {}

    float alpha() const { return m_alpha; }
    /// D(h): the density of microfacet normals per projected area.
    float d(Vec3 h) const;
    /// Lambda(w), from which G1 = 1 / (1 + Lambda) and G2 = 1 / (1 + Lambda(wo) + Lambda(wi)).
    float lambda(Vec3 w) const;
    float g1(Vec3 w) const { return 1 / (1 + lambda(w)); }
    float g2(Vec3 wo, Vec3 wi) const { return 1 / (1 + lambda(wo) + lambda(wi)); }
    /// A microfacet normal visible from `wo` (wo.z > 0), with density G1(wo) max(0, wo.h) D(h) / wo.z.
    Vec3 sample_visible_normal(Vec3 wo, Vec2 u) const;
    /// The solid-angle pdf of the reflected direction wi = reflect(wo, h) for that sampling.
    float pdf_reflection(Vec3 wo, Vec3 wi) const;

private:
    float m_alpha;
};

/// \brief Directional albedo of single-scattering GGX reflection, from tables over (cos theta,
/// roughness) filled once by quadrature. `e` is with Fresnel 1, `e_schlick` with Fresnel
/// (1 - wo.h)^5, so that a Schlick Fresnel F0 + (1 - F0)(1 - wo.h)^5 gives F0 e + (1 - F0) e_schlick.
/// `roughness` is glTF's (alpha = roughness^2). The averages are 2 * integral of E(mu) mu dmu.
struct GgxAlbedo {
    float e = 0, e_schlick = 0;
};
GgxAlbedo ggx_albedo(float cos_theta, float roughness);
GgxAlbedo ggx_average_albedo(float roughness);

/// The smallest roughness the pbr BSDF uses: below it GGX in float precision is a spike.
constexpr float min_pbr_roughness = 0.03f;

}  // namespace steadylight
