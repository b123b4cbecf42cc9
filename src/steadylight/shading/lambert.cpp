// Lambertian (ideal diffuse) reflection: f = R / pi, sampled by the cosine.
#include <cmath>

#include "steadylight/base/sampling.h"
#include "steadylight/shading/bsdf.h"

namespace steadylight {
namespace {

class Lambert final : public Bsdf {
public:
    explicit Lambert(Rgb reflectance) : m_reflectance(reflectance) {}

    bool is_diffuse() const override { return true; }
    Rgb diffuse_reflectance(Vec3) const override { return m_reflectance; }

    Rgb eval(Vec3 wo, Vec3 wi) const override { return wo.z * wi.z > 0 ? m_reflectance * inv_pi : Rgb{}; }

    float pdf(Vec3 wo, Vec3 wi) const override { return wo.z * wi.z > 0 ? cosine_hemisphere_pdf(std::abs(wi.z)) : 0; }

    std::optional<BsdfSample> sample(Vec3 wo, Vec2 u, float, TransportMode) const override {
        Vec3 wi = sample_cosine_hemisphere(u);
        if (wi.z <= 0 || wo.z == 0) return std::nullopt;
        if (wo.z < 0) wi.z = -wi.z;
        return BsdfSample{wi, m_reflectance, cosine_hemisphere_pdf(std::abs(wi.z)), false, true};
    }

private:
    Rgb m_reflectance;
};

}  // namespace

std::unique_ptr<Bsdf> make_lambert(Rgb reflectance) { return std::make_unique<Lambert>(reflectance); }

}  // namespace steadylight
