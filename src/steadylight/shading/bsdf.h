// BSDFs: how light scatters at a surface, in the local shading frame where the normal is +z
// (pbrt-v4 conventions: wo and wi both point away from the surface). The reflective BSDFs are
// two-sided; the dielectric tells inside (wo.z < 0) from outside. One file per implementation.
#pragma once

#include <memory>
#include <optional>

#include "steadylight/base/color.h"
#include "steadylight/base/vec.h"
#include "steadylight/scene/scene_desc.h"

namespace steadylight {

/// Radiance flows from lights to the camera; importance (photons) the other way. They differ
/// only for refraction, where radiance is scaled by (eta_i / eta_t)^2 (Veach 1997, §5.2).
enum class TransportMode { radiance, importance };

struct BsdfSample {
    Vec3 wi;
    Rgb weight;     // f * |cos(wi)| / pdf
    float pdf = 0;  // solid angle; for delta lobes the discrete probability of the lobe
    bool is_delta = false;
    bool diffuse = false;  // drawn from the diffuse base's strategy (photon paths stop being caustic)
};

class Bsdf {
public:
    virtual ~Bsdf() = default;
    /// f(wo, wi); zero for delta BSDFs.
    virtual Rgb eval(Vec3 wo, Vec3 wi) const = 0;
    /// The solid-angle pdf with which sample() returns wi; zero for delta BSDFs.
    virtual float pdf(Vec3 wo, Vec3 wi) const = 0;
    /// Samples an incident direction; `u_lobe` chooses between lobes.
    virtual std::optional<BsdfSample> sample(Vec3 wo, Vec2 u, float u_lobe, TransportMode mode) const = 0;
    /// True when every lobe is a delta: no light sampling is possible.
    virtual bool is_delta() const { return false; }
    /// True when the BSDF has a diffuse base (Lambert, or the base of a coated pbr material):
    /// the surfaces where photons are stored and irradiance is cached; the base's reflected
    /// radiance is diffuse_reflectance(wo) / pi times the irradiance (docs/materials.md).
    virtual bool is_diffuse() const { return false; }
    /// The diffuse base's albedo seen from `wo` (local frame): what a coat leaves of it.
    virtual Rgb diffuse_reflectance(Vec3 wo) const {
        (void)wo;
        return {};
    }
    /// For a BSDF with a diffuse base: its other lobes (a coat's or a metal's reflection), which
    /// are traced; nullptr when there are none (Lambert).
    virtual std::unique_ptr<Bsdf> non_diffuse_part() const { return nullptr; }
};

/// The parameters of glTF's metallic-roughness material at one point (pbr.cpp).
struct PbrParams {
    Rgb base{0.8f, 0.8f, 0.8f};  // base colour: the diffuse albedo, and a metal's normal-incidence Fresnel
    float metallic = 0;
    float roughness = 0.5f;  // alpha = roughness^2
    float f0 = 0.04f;        // the coat's normal-incidence Fresnel, from pbr_f0()
    float specular = 1;      // scales the coat's whole Fresnel (KHR_materials_specular)
};

std::unique_ptr<Bsdf> make_lambert(Rgb reflectance);
std::unique_ptr<Bsdf> make_mirror(Rgb reflectance);
std::unique_ptr<Bsdf> make_dielectric(float ior, Rgb transmittance);
/// Rough glass (GGX microfacets, Walter et al. 2007); `roughness` is clamped to
/// [min_pbr_roughness, 1]. Its eval() is f for radiance; sample() follows `mode`.
std::unique_ptr<Bsdf> make_rough_dielectric(float ior, float roughness, Rgb transmittance);
std::unique_ptr<Bsdf> make_glossy(Rgb reflectance, float roughness);
std::unique_ptr<Bsdf> make_pbr(const PbrParams& params);
/// The BSDF of an untextured material (a textured one is made per point: material_eval.h).
std::unique_ptr<Bsdf> make_bsdf(const MaterialDesc& material);

/// The coat's normal-incidence Fresnel for index `ior`, scaled by `specular_color`
/// (KHR_materials_specular), at most 1.
float pbr_f0(float ior, float specular_color);
/// The pbr parameters of an untextured material.
PbrParams pbr_params(const MaterialDesc& material);

/// Unpolarised Fresnel reflectance of a smooth dielectric boundary; `cos_i` is signed
/// (negative: arriving from inside), `ior` = inside / outside.
float fresnel_dielectric(float cos_i, float ior);

}  // namespace steadylight
