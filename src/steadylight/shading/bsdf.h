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
    /// True for ideal diffuse reflection: the surfaces where photons are stored and irradiance
    /// is cached; their reflected radiance is diffuse_reflectance() / pi times the irradiance.
    virtual bool is_diffuse() const { return false; }
    virtual Rgb diffuse_reflectance() const { return {}; }
};

std::unique_ptr<Bsdf> make_lambert(Rgb reflectance);
std::unique_ptr<Bsdf> make_mirror(Rgb reflectance);
std::unique_ptr<Bsdf> make_dielectric(float ior, Rgb transmittance);
std::unique_ptr<Bsdf> make_glossy(Rgb reflectance, float roughness);
std::unique_ptr<Bsdf> make_bsdf(const MaterialDesc& material);

/// Unpolarised Fresnel reflectance of a smooth dielectric boundary; `cos_i` is signed
/// (negative: arriving from inside), `ior` = inside / outside.
float fresnel_dielectric(float cos_i, float ior);

}  // namespace steadylight
