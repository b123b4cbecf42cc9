// Point and spot lights: radiant intensity from one point, a spot light limited to a cone with
// a smooth falloff at its edge. They cannot be hit by rays, only sampled.
#include <algorithm>
#include <cmath>

#include "steadylight/base/sampling.h"

#include "steadylight/shading/light.h"

namespace steadylight {
namespace {

class PointLight final : public Light {
public:
    PointLight(const PointLightDesc& desc, const PointLightPose& pose)
        : m_type(desc.type),
          m_position(pose.position),
          m_direction(pose.direction),
          m_intensity(pose.intensity),
          m_cos_cone(std::cos(desc.cone_angle_deg * pi / 180)),
          m_cos_falloff_start(std::cos(desc.falloff_start_deg * pi / 180)) {}

    std::optional<LightSample> sample_li(Vec3 ref, Vec2, Vec3) const override {
        LightSample s;
        s.p = m_position;
        const Vec3 d = s.p - ref;
        s.distance = length(d);
        if (!(s.distance > 0)) return std::nullopt;
        s.wi = d / s.distance;
        s.Li = m_intensity * (falloff(-s.wi) / (s.distance * s.distance));
        s.pdf = 1;
        s.is_delta = true;
        if (is_black(s.Li)) return std::nullopt;
        return s;
    }

    float pdf_li(Vec3, Vec3, Vec3) const override { return 0; }

    float power() const override {
        const float lum = luminance(m_intensity);
        if (m_type == PointLightType::point) return 4 * pi * lum;
        // The cone's solid angle up to the middle of the falloff band.
        return 2 * pi * (1 - 0.5f * (m_cos_cone + m_cos_falloff_start)) * lum;
    }

    float importance(Vec3 ref, Vec3 n) const override {
        const Vec3 wi = normalize(m_position - ref);
        return importance_bound(luminance(m_intensity) * falloff(-wi), ref, n, m_position, 0, {});
    }

    std::optional<EmissionSample> sample_emission(Vec2, Vec2 u_direction) const override {
        EmissionSample s;
        s.p = m_position;
        if (m_type == PointLightType::point) {
            s.d = sample_uniform_sphere(u_direction);
            s.power = m_intensity * (4 * pi);
            return s;
        }
        // Uniform directions in the spot's cone, weighted by its falloff.
        s.d = OrthonormalBasis::from_normal(m_direction).to_world(sample_uniform_cone(u_direction, m_cos_cone));
        s.power = m_intensity * (falloff(s.d) / uniform_cone_pdf(m_cos_cone));
        return s;
    }

    EmissionPoint sample_emission_point(Vec2) const override {
        EmissionPoint at;
        at.p = m_position;
        at.pdf = 1;
        return at;
    }

    Rgb emitted_intensity(const EmissionPoint&, Vec3 d) const override { return m_intensity * falloff(d); }
    BoundingSphere bounds() const override { return {m_position, 0}; }

private:
    /// 1 inside the spot's inner cone, 0 outside it, smoothstep between (pbrt-v4 SpotLight).
    float falloff(Vec3 w) const {
        if (m_type == PointLightType::point) return 1;
        const float cos_theta = dot(w, m_direction);
        if (cos_theta >= m_cos_falloff_start) return 1;
        if (cos_theta <= m_cos_cone) return 0;
        const float t = (cos_theta - m_cos_cone) / (m_cos_falloff_start - m_cos_cone);
        return t * t * (3 - 2 * t);
    }

    // Where the lamp is, where it points and its intensity at this frame.
    PointLightType m_type;
    Vec3 m_position, m_direction;
    Rgb m_intensity;
    float m_cos_cone;
    float m_cos_falloff_start;
};

}  // namespace

std::unique_ptr<Light> make_point_light(const PointLightDesc& desc, const PointLightPose& pose) {
    return std::make_unique<PointLight>(desc, pose);
}

}  // namespace steadylight
