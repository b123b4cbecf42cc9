#include "steadylight/shading/bsdf.h"
#include "steadylight/shading/microfacet.h"

#include <cmath>
#include <utility>

namespace steadylight {

std::unique_ptr<Bsdf> make_bsdf(const MaterialDesc& material) {
    switch (material.type) {
        case MaterialType::lambert:
            return make_lambert(material.reflectance);
        case MaterialType::mirror:
            return make_mirror(material.reflectance);
        case MaterialType::dielectric:
            // Below GGX's smallest roughness glass is smooth: a delta BSDF, as it always was. The
            // JSON and glTF readers set 0 for smooth glass; a MaterialDesc built in code keeps
            // the default 0.3, rough glass, unless it says .roughness = 0.
            if (material.roughness < min_pbr_roughness) return make_dielectric(material.ior, material.transmittance);
            return make_rough_dielectric(material.ior, material.roughness, material.transmittance);
        case MaterialType::glossy:
            return make_glossy(material.reflectance, material.roughness);
        case MaterialType::pbr:
            return make_pbr(pbr_params(material));
    }
    return make_lambert(material.reflectance);
}

PbrParams pbr_params(const MaterialDesc& material) {
    return {.base = material.reflectance,
            .metallic = material.metallic,
            .roughness = material.roughness,
            .f0 = pbr_f0(material.ior, material.specular_color),
            .specular = material.specular};
}

float fresnel_dielectric(float cos_i, float ior) {
    float eta = ior;
    if (cos_i < 0) {
        eta = 1 / eta;
        cos_i = -cos_i;
    }
    const float sin2_t = (1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1) return 1;  // total internal reflection
    const float cos_t = std::sqrt(1 - sin2_t);
    const float r_parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const float r_perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return (r_parallel * r_parallel + r_perpendicular * r_perpendicular) / 2;
}

}  // namespace steadylight
