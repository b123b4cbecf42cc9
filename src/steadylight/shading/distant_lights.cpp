// Lights from far away: the sun (parallel light within a small cone, or exactly parallel) and
// the world (light from every direction). Seen from a shading point they are directions, not
// points: a LightSample's distance is infinite and its shadow ray open-ended (shadow_ray()). A
// ray that leaves the scene sees them (escaped_radiance()). Their photons start on a disc as
// large as the scene's animation bounds (Scene::bounds()), just outside it, facing the light.
#include <algorithm>
#include <cmath>

#include "steadylight/base/sampling.h"
#include "steadylight/shading/light.h"

namespace steadylight {
namespace {

/// A point on the disc of radius `radius` about `center`, perpendicular to unit `axis`.
Vec3 point_on_disc(Vec3 center, Vec3 axis, float radius, Vec2 u) {
    const float r = radius * std::sqrt(u.x), phi = 2 * pi * u.y;
    return center + OrthonormalBasis::from_normal(axis).to_world({r * std::cos(phi), r * std::sin(phi), 0});
}

/// Where a photon of direction `d` (travelling) starts: on the disc that covers `scene`, facing
/// the light, just outside the scene's sphere. Its pdf is 1 / disc_area(scene).
Vec3 distant_photon_origin(const BoundingSphere& scene, Vec3 d, Vec2 u) {
    const float radius = std::max(scene.radius, 1e-3f);
    return point_on_disc(scene.center - d * (radius * 1.01f), d, radius, u);
}

float disc_area(const BoundingSphere& scene) {
    return pi * std::max(scene.radius, 1e-3f) * std::max(scene.radius, 1e-3f);
}

/// A point far along `wi` from `ref`, beyond the scene, for code that wants a light's position.
Vec3 far_point(const BoundingSphere& scene, Vec3 ref, Vec3 wi) {
    return ref + wi * (2 * (std::max(scene.radius, 1e-3f) + length(ref - scene.center)));
}

class SunLight final : public Light {
public:
    SunLight(const SunLightDesc& desc, const BoundingSphere& scene)
        : m_to_sun(-normalize(desc.direction)),
          m_irradiance(desc.irradiance),
          m_cos_max(std::cos(desc.angle_deg * pi / 360)),
          m_delta(desc.angle_deg <= 0 || m_cos_max >= 1),
          m_radiance(m_delta ? Rgb{} : desc.irradiance * uniform_cone_pdf(m_cos_max)),
          m_scene(scene) {}

    std::optional<LightSample> sample_li(Vec3 ref, Vec2 u, Vec3) const override {
        LightSample s;
        s.wi = m_delta ? m_to_sun : OrthonormalBasis::from_normal(m_to_sun).to_world(sample_uniform_cone(u, m_cos_max));
        s.p = far_point(m_scene, ref, s.wi);
        s.distance = infinity;
        s.Li = m_delta ? m_irradiance : m_radiance;
        s.pdf = m_delta ? 1 : uniform_cone_pdf(m_cos_max);
        s.is_delta = m_delta;
        return s;
    }

    float pdf_li(Vec3, Vec3, Vec3) const override { return 0; }
    float pdf_escaped(Vec3 w, Vec3) const override { return inside_cone(w) ? uniform_cone_pdf(m_cos_max) : 0; }
    Rgb escaped_radiance(Vec3 w) const override { return inside_cone(w) ? m_radiance : Rgb{}; }

    float power() const override { return luminance(m_irradiance) * disc_area(m_scene); }

    float importance(Vec3, Vec3 n) const override {
        // The cosine with the nearest direction of the cone.
        const float sin_max = std::sqrt(std::max(0.0f, 1 - m_cos_max * m_cos_max));
        const float cos_n = dot(n, m_to_sun);
        const float sin_n = std::sqrt(std::max(0.0f, 1 - cos_n * cos_n));
        const float cos_bound = cos_n * m_cos_max + sin_n * sin_max;
        return luminance(m_irradiance) * std::max(0.0f, cos_bound);
    }

    std::optional<EmissionSample> sample_emission(Vec2 u_position, Vec2 u_direction) const override {
        EmissionSample s;
        const Vec3 to_light =
            m_delta ? m_to_sun
                    : OrthonormalBasis::from_normal(m_to_sun).to_world(sample_uniform_cone(u_direction, m_cos_max));
        s.d = -to_light;
        s.p = distant_photon_origin(m_scene, s.d, u_position);
        // L / (pdf_direction pdf_position) = (E / Ω) Ω A: the irradiance over the disc.
        s.power = m_irradiance * disc_area(m_scene);
        return s;
    }

    /// Photons from far away are not aimed at caustic targets: a zero pdf says so (emit()).
    EmissionPoint sample_emission_point(Vec2) const override { return {}; }
    Rgb emitted_intensity(const EmissionPoint&, Vec3) const override { return {}; }

    /// Every shadow ray towards the sun lies in the hull of a scene point and this sphere: far
    /// beyond the scene towards the sun, wide enough for the cone's spread over that distance.
    BoundingSphere bounds() const override {
        const float radius = std::max(m_scene.radius, 1e-3f);
        const float distance = 1000 * radius;
        const float tan_max = std::sqrt(std::max(0.0f, 1 - m_cos_max * m_cos_max)) / m_cos_max;
        return {m_scene.center + m_to_sun * distance, radius + (distance + 2 * radius) * tan_max};
    }

private:
    bool inside_cone(Vec3 w) const { return !m_delta && dot(w, m_to_sun) >= m_cos_max; }

    Vec3 m_to_sun;
    Rgb m_irradiance;
    float m_cos_max;
    bool m_delta;
    Rgb m_radiance;  // over the disc, when it has one
    BoundingSphere m_scene;
};

class WorldLight final : public Light {
public:
    WorldLight(const WorldDesc& desc, const BoundingSphere& scene)
        : m_map(desc.radiance), m_cosine_share(m_map->is_uniform() ? 0.75f : 0.25f), m_scene(scene) {}

    /// Facing a normal: cosine-weighted about it with probability m_cosine_share, else by the
    /// map (uniform over the sphere for a uniform colour; by luminance times solid angle for an
    /// image, which finds a small bright sun in it), so that every lit direction keeps a chance
    /// (light from behind a rough pane).
    std::optional<LightSample> sample_li(Vec3 ref, Vec2 u, Vec3 n) const override {
        LightSample s;
        if (length2(n) > 0 && u.x < m_cosine_share) {
            s.wi = OrthonormalBasis::from_normal(n).to_world(sample_cosine_hemisphere({u.x / m_cosine_share, u.y}));
        } else {
            const float rest = length2(n) > 0 ? (u.x - m_cosine_share) / (1 - m_cosine_share) : u.x;
            const std::optional<EnvironmentMap::Sample> sample = m_map->sample({std::min(rest, 0x1.fffffep-1f), u.y});
            if (!sample) return std::nullopt;
            s.wi = sample->w;
        }
        s.p = far_point(m_scene, ref, s.wi);
        s.distance = infinity;
        s.Li = m_map->radiance(s.wi);
        s.pdf = pdf_escaped(s.wi, n);
        if (!(s.pdf > 0)) return std::nullopt;
        return s;
    }

    float pdf_li(Vec3, Vec3, Vec3) const override { return 0; }
    float pdf_escaped(Vec3 w, Vec3 n) const override {
        if (!(length2(n) > 0)) return m_map->pdf(w);
        return m_cosine_share * std::max(0.0f, dot(w, n)) * inv_pi + (1 - m_cosine_share) * m_map->pdf(w);
    }
    Rgb escaped_radiance(Vec3 w) const override { return m_map->radiance(w); }

    /// What enters the scene's sphere: the mean radiance L from every direction through a disc
    /// of its radius, 4π L A.
    float power() const override { return m_map->mean_luminance() * 4 * pi * disc_area(m_scene); }
    /// A uniform world gives π L; an image at most all its light from one direction, 4π L.
    float importance(Vec3, Vec3) const override {
        return m_map->mean_luminance() * (m_map->is_uniform() ? pi : 4 * pi);
    }

    std::optional<EmissionSample> sample_emission(Vec2 u_position, Vec2 u_direction) const override {
        const std::optional<EnvironmentMap::Sample> sample = m_map->sample(u_direction);
        if (!sample || !(sample->pdf > 0)) return std::nullopt;
        EmissionSample s;
        s.d = -sample->w;
        s.p = distant_photon_origin(m_scene, s.d, u_position);
        s.power = sample->radiance * (disc_area(m_scene) / sample->pdf);
        return s;
    }

    EmissionPoint sample_emission_point(Vec2) const override { return {}; }
    Rgb emitted_intensity(const EmissionPoint&, Vec3) const override { return {}; }

    /// Light from every direction: a sphere without bounds, which meets every segment
    /// (may_meet_segments).
    BoundingSphere bounds() const override { return {m_scene.center, infinity}; }

private:
    std::shared_ptr<const EnvironmentMap> m_map;
    float m_cosine_share;
    BoundingSphere m_scene;
};

}  // namespace

std::unique_ptr<Light> make_sun_light(const SunLightDesc& desc, const BoundingSphere& scene) {
    return std::make_unique<SunLight>(desc, scene);
}

std::unique_ptr<Light> make_world_light(const WorldDesc& desc, const BoundingSphere& scene) {
    return std::make_unique<WorldLight>(desc, scene);
}

}  // namespace steadylight
