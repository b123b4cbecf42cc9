// A perfect mirror: all light leaves in the mirror direction, tinted by the reflectance.
#include "steadylight/shading/bsdf.h"

namespace steadylight {
namespace {

class Mirror final : public Bsdf {
public:
    explicit Mirror(Rgb reflectance) : m_reflectance(reflectance) {}

    Rgb eval(Vec3, Vec3) const override { return {}; }
    float pdf(Vec3, Vec3) const override { return 0; }
    bool is_delta() const override { return true; }

    std::optional<BsdfSample> sample(Vec3 wo, Vec2, float, TransportMode) const override {
        if (wo.z == 0) return std::nullopt;
        return BsdfSample{{-wo.x, -wo.y, wo.z}, m_reflectance, 1, true};
    }

private:
    Rgb m_reflectance;
};

}  // namespace

std::unique_ptr<Bsdf> make_mirror(Rgb reflectance) { return std::make_unique<Mirror>(reflectance); }

}  // namespace steadylight
