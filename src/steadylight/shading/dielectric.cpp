// A smooth dielectric boundary (glass, water): Fresnel-weighted choice between mirror reflection
// and refraction by Snell's law. The normal points outside; `ior` is inside over outside.
#include <cmath>

#include "steadylight/shading/bsdf.h"

namespace steadylight {
namespace {

class Dielectric final : public Bsdf {
public:
    Dielectric(float ior, Rgb transmittance) : m_ior(ior), m_transmittance(transmittance) {}

    Rgb eval(Vec3, Vec3) const override { return {}; }
    float pdf(Vec3, Vec3) const override { return 0; }
    bool is_delta() const override { return true; }

    std::optional<BsdfSample> sample(Vec3 wo, Vec2, float u_lobe, TransportMode mode) const override {
        if (wo.z == 0) return std::nullopt;
        const float reflectance = fresnel_dielectric(wo.z, m_ior);
        if (u_lobe < reflectance) return BsdfSample{{-wo.x, -wo.y, wo.z}, {1, 1, 1}, reflectance, true};

        // Refract: eta = eta_t / eta_i across the boundary that wo arrives through.
        const bool entering = wo.z > 0;
        const float eta = entering ? m_ior : 1 / m_ior;
        const float cos_i = std::abs(wo.z);
        const float sin2_t = (1 - cos_i * cos_i) / (eta * eta);
        const float cos_t = std::sqrt(std::max(0.0f, 1 - sin2_t));
        const Vec3 wi{-wo.x / eta, -wo.y / eta, entering ? -cos_t : cos_t};
        // Radiance is compressed into the denser medium's smaller solid angle.
        const float scale = mode == TransportMode::radiance ? 1 / (eta * eta) : 1.0f;
        return BsdfSample{wi, m_transmittance * scale, 1 - reflectance, true};
    }

private:
    float m_ior;
    Rgb m_transmittance;
};

}  // namespace

std::unique_ptr<Bsdf> make_dielectric(float ior, Rgb transmittance) {
    return std::make_unique<Dielectric>(ior, transmittance);
}

}  // namespace steadylight
