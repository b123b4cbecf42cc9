// Lights from far away: the sun (parallel light within a small cone, or exactly parallel) and
// the world (light from every direction). Seen from a shading point they are directions, not
// points: a LightSample's distance is infinite and its shadow ray open-ended (shadow_ray()). A
// ray that leaves the scene sees them (escaped_radiance()). Their photons start on a disc as
// large as the scene's animation bounds (Scene::bounds()), just outside it, facing the light.
//
// With portals (PortalDesc: the windows of an interior), photons are aimed through them instead:
// a point on a portal, a direction from outside through it, the photon started outside the scene
// on the line back from that point; the light that enters by no portal is then not traced as
// photons (as Cycles' portals, they must mark every opening). The world's direct light at a point
// inside samples the portals by solid angle besides its other strategies.
#include <algorithm>
#include <cmath>

#include "steadylight/base/ray.h"
#include "steadylight/base/sampling.h"
#include "steadylight/shading/light.h"
#include "steadylight/shading/spherical_rectangle.h"

namespace steadylight {
namespace {

/// A point on the disc of radius `radius` about `center`, perpendicular to unit `axis`.
Vec3 point_on_disc(Vec3 center, Vec3 axis, float radius, Vec2 u) {
    const float r = radius * std::sqrt(u.x), phi = 2 * pi * u.y;
    return center + OrthonormalBasis::from_normal(axis).to_world({r * std::cos(phi), r * std::sin(phi), 0});
}

float disc_area(const BoundingSphere& scene) {
    return pi * std::max(scene.radius, 1e-3f) * std::max(scene.radius, 1e-3f);
}

/// Where a photon of direction `d` (travelling) starts: on the disc that covers `scene`, facing
/// the light, just outside the scene's sphere, where `targets` aims it when there are some; and
/// the density of that start by area (1 / disc_area(scene) without targets).
DistantPhotonTargets::Start distant_photon_start(const BoundingSphere& scene, const DistantPhotonTargets* targets,
                                                 Vec3 d, Vec2 u) {
    if (targets) return targets->sample_start(d, u);
    const float radius = std::max(scene.radius, 1e-3f);
    return {point_on_disc(scene.center - d * (radius * 1.01f), d, radius, u), 1 / disc_area(scene)};
}

/// A point far along `wi` from `ref`, beyond the scene, for code that wants a light's position.
Vec3 far_point(const BoundingSphere& scene, Vec3 ref, Vec3 wi) {
    return ref + wi * (2 * (std::max(scene.radius, 1e-3f) + length(ref - scene.center)));
}

/// The portals as light from far away uses them: photons aimed through them, and the world's
/// direct light sampled through them.
class Portals {
public:
    explicit Portals(const std::vector<PortalDesc>& portals) {
        for (const PortalDesc& portal : portals) {
            m_rectangles.push_back({portal.corner, portal.edge_u, portal.edge_v});
            m_normals.push_back(portal.inward_normal());
            m_areas.push_back(portal.area());
            m_edge_lengths.push_back({length(portal.edge_u), length(portal.edge_v)});
            m_total_area += portal.area();
        }
    }

    bool empty() const { return m_rectangles.empty(); }

    /// A photon's way in for travel direction `d` (unit): a point on a portal chosen in
    /// proportion to its area facing d, and the flux factor Σ A_i cos⁺(d, n_i) (irradiance
    /// across d times it is the power entering); nothing when no portal faces d.
    struct Entry {
        Vec3 p;
        float projected_area = 0;
    };
    std::optional<Entry> entry_for(Vec3 d, Vec2 u) const {
        float total = 0;
        for (size_t i = 0; i < m_rectangles.size(); ++i) total += projected_area(i, d);
        if (!(total > 0)) return std::nullopt;
        float target = u.x * total;
        size_t i = 0;
        for (; i + 1 < m_rectangles.size() && target >= projected_area(i, d); ++i) target -= projected_area(i, d);
        const float s = std::clamp(target / projected_area(i, d), 0.0f, 0x1.fffffep-1f);
        return Entry{point_on(i, {s, u.y}), total};
    }

    /// A point uniformly by area over all portals, and the inward normal there.
    std::pair<Vec3, Vec3> uniform_point(Vec2 u) const {
        float target = u.x * m_total_area;
        size_t i = 0;
        for (; i + 1 < m_rectangles.size() && target >= m_areas[i]; ++i) target -= m_areas[i];
        const float s = std::clamp(target / m_areas[i], 0.0f, 0x1.fffffep-1f);
        return {point_on(i, {s, u.y}), m_normals[i]};
    }
    float total_area() const { return m_total_area; }

    /// Whether `ref` sees some portal from inside (from the side its normal faces).
    bool seen_from_inside(Vec3 ref) const {
        for (size_t i = 0; i < m_rectangles.size(); ++i)
            if (faces(i, ref)) return true;
        return false;
    }
    /// A direction from `ref` through a portal that faces it (chosen uniformly among those),
    /// uniform in the portal's solid angle.
    std::optional<Vec3> sample_direction(Vec3 ref, Vec2 u) const {
        const int facing = facing_count(ref);
        if (facing == 0) return std::nullopt;
        int k = std::min(int(u.x * float(facing)), facing - 1);
        const float rest = u.x * float(facing) - float(k);
        for (size_t i = 0; i < m_rectangles.size(); ++i) {
            if (!faces(i, ref) || k-- > 0) continue;
            const SphericalRectangle seen(m_rectangles[i], ref);
            if (!(seen.solid_angle() > min_solid_angle)) return std::nullopt;
            return normalize(seen.sample({std::min(rest, 0x1.fffffep-1f), u.y}) - ref);
        }
        return std::nullopt;
    }
    /// The solid-angle density sample_direction() gives `w` at `ref`.
    float pdf(Vec3 ref, Vec3 w) const {
        const int facing = facing_count(ref);
        float pdf = 0;
        for (size_t i = 0; i < m_rectangles.size(); ++i) {
            if (!faces(i, ref) || !crosses(i, ref, w)) continue;
            const float solid_angle = SphericalRectangle(m_rectangles[i], ref).solid_angle();
            if (solid_angle > min_solid_angle) pdf += 1 / (float(facing) * solid_angle);
        }
        return pdf;
    }

private:
    static constexpr float min_solid_angle = 1e-7f;

    float projected_area(size_t i, Vec3 d) const { return m_areas[i] * std::max(0.0f, dot(d, m_normals[i])); }
    Vec3 point_on(size_t i, Vec2 u) const {
        return m_rectangles[i].corner + m_rectangles[i].edge_u * u.x + m_rectangles[i].edge_v * u.y;
    }
    bool faces(size_t i, Vec3 ref) const { return dot(ref - m_rectangles[i].corner, m_normals[i]) > 0; }
    int facing_count(Vec3 ref) const {
        int n = 0;
        for (size_t i = 0; i < m_rectangles.size(); ++i) n += faces(i, ref);
        return n;
    }
    /// Whether the ray from `ref` along `w` passes through portal i, or so near its rim that a
    /// shadow ray from `ref` may: shadow rays start lifted off their surface (spawn_ray(), by
    /// ray_epsilon()), and a lifted ray can pass through the opening where the line from `ref`
    /// meets the wall beside it. Such a ray, found unoccluded, would otherwise be weighed by the
    /// other strategies' density alone, a hundred times too small, and light its pixel as a
    /// bright speck. The lift moves a ray's crossing by at most ray_epsilon(ref) (1 + 1 / cos),
    /// cos between the ray and the portal's normal; the rim taken is twice that, its cos kept
    /// above 0.1. Directions within it that the tracer finds blocked add nothing whatever their
    /// density; the others, which the portal sampler never gives, are weighed a little low: a
    /// share of the light of about the rim's width over the portal's, far below the noise.
    bool crosses(size_t i, Vec3 ref, Vec3 w) const {
        const Rectangle& r = m_rectangles[i];
        const float along = dot(w, m_normals[i]);
        if (!(along < 0)) return false;  // from inside, a way out goes against the inward normal
        const Vec3 q = ref + w * (dot(r.corner - ref, m_normals[i]) / along) - r.corner;
        const float rim = 2 * ray_epsilon(ref) * (1 + 1 / std::max(-along, 0.1f));
        const Vec2 edges = m_edge_lengths[i];
        const float u = dot(q, r.edge_u) / edges.x, v = dot(q, r.edge_v) / edges.y;
        return u >= -rim && u <= edges.x + rim && v >= -rim && v <= edges.y + rim;
    }

    std::vector<Rectangle> m_rectangles;
    std::vector<Vec3> m_normals;
    std::vector<float> m_areas;
    std::vector<Vec2> m_edge_lengths;  // |edge_u|, |edge_v|
    float m_total_area = 0;
};

/// Where a photon travelling `d` through point `p` of a portal starts: outside the scene's
/// sphere, on the line back from p.
Vec3 origin_outside(const BoundingSphere& scene, Vec3 p, Vec3 d) {
    return p - d * (length(p - scene.center) + std::max(scene.radius, 1e-3f) * 1.01f);
}

class SunLight final : public Light {
public:
    SunLight(const SunLightDesc& desc, Vec3 direction, const BoundingSphere& scene,
             const std::vector<PortalDesc>& portals, const DistantPhotonTargets* targets)
        : m_to_sun(-normalize(direction)),
          m_irradiance(desc.irradiance),
          m_cos_max(std::cos(desc.angle_deg * pi / 360)),
          m_delta(desc.angle_deg <= 0 || m_cos_max >= 1),
          m_radiance(m_delta ? Rgb{} : desc.irradiance * uniform_cone_pdf(m_cos_max)),
          m_scene(scene),
          m_portals(portals),
          m_targets(targets) {}

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
    float pdf_escaped(Vec3, Vec3 w, Vec3) const override { return inside_cone(w) ? uniform_cone_pdf(m_cos_max) : 0; }
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
        if (!m_portals.empty()) {
            // Through a portal: the irradiance times the portals' area facing the light. A
            // direction no portal faces lets no light in: a photon without power.
            const std::optional<Portals::Entry> entry = m_portals.entry_for(s.d, u_position);
            s.p = entry ? origin_outside(m_scene, entry->p, s.d) : m_scene.center;
            s.power = entry ? m_irradiance * entry->projected_area : Rgb{};
            return s;
        }
        const DistantPhotonTargets::Start start = distant_photon_start(m_scene, m_targets, s.d, u_position);
        s.p = start.p;
        // L / (pdf_direction pdf_position) = (E / Ω) Ω / pdf_position: the irradiance over the
        // disc's density (its area, without targets).
        s.power = start.pdf > 0 ? m_irradiance / start.pdf : Rgb{};
        return s;
    }

    /// Photons from far away are not aimed at caustic targets: a zero pdf says so (emit()).
    EmissionPoint sample_emission_point(Vec2) const override { return {}; }
    Rgb emitted_intensity(const EmissionPoint&, Vec3) const override { return {}; }

    /// No place to bound: pixel reuse follows the shadow rays' directions (Light::bounds()).
    BoundingSphere bounds() const override { return {}; }

private:
    bool inside_cone(Vec3 w) const { return !m_delta && dot(w, m_to_sun) >= m_cos_max; }

    Vec3 m_to_sun;
    Rgb m_irradiance;
    float m_cos_max;
    bool m_delta;
    Rgb m_radiance;  // over the disc, when it has one
    BoundingSphere m_scene;
    Portals m_portals;
    const DistantPhotonTargets* m_targets;
};

class WorldLight final : public Light {
public:
    WorldLight(const WorldDesc& desc, const BoundingSphere& scene, const std::vector<PortalDesc>& portals,
               const DistantPhotonTargets* targets)
        : m_map(desc.radiance), m_scene(scene), m_portals(portals), m_targets(targets) {
        if (m_targets && m_portals.empty())
            m_aimed = m_targets->aimed_directions([this](Vec3 d) { return luminance(m_map->radiance(-d)); });
    }

    bool samples_by_normal() const override { return true; }

    /// Facing a normal, a mix (Shares): for a uniform colour cosine-weighted about it three times
    /// in four, else uniformly; for an image mostly by its light times the cosine
    /// (EnvironmentMap::sample_facing), and by its light alone (which finds a small bright sun
    /// exactly) or cosine-weighted besides; so that every lit direction keeps a chance (light
    /// from behind a rough pane). Inside a room with portals, through a portal half of the time
    /// (three times in four for a uniform colour), else by the map.
    std::optional<LightSample> sample_li(Vec3 ref, Vec2 u, Vec3 n) const override {
        const Shares shares = shares_at(ref, n);
        LightSample s;
        // u.x chooses the strategy and, rescaled to [0, 1), goes on into it.
        const auto rescaled = [&](float begin, float share) {
            return Vec2{std::min((u.x - begin) / share, 0x1.fffffep-1f), u.y};
        };
        const float facing_begin = shares.portal + shares.cosine, map_begin = facing_begin + shares.facing;
        if (u.x < shares.portal) {
            const std::optional<Vec3> w = m_portals.sample_direction(ref, rescaled(0, shares.portal));
            if (!w) return std::nullopt;
            s.wi = *w;
        } else if (u.x < facing_begin) {
            s.wi = OrthonormalBasis::from_normal(n).to_world(
                sample_cosine_hemisphere(rescaled(shares.portal, shares.cosine)));
        } else {
            const std::optional<EnvironmentMap::Sample> sample =
                u.x < map_begin ? m_map->sample_facing(n, rescaled(facing_begin, shares.facing))
                                : m_map->sample(rescaled(map_begin, 1 - map_begin));
            if (!sample) return std::nullopt;
            s.wi = sample->w;
        }
        s.p = far_point(m_scene, ref, s.wi);
        s.distance = infinity;
        s.Li = m_map->radiance(s.wi);
        s.pdf = pdf_escaped(ref, s.wi, n);
        if (!(s.pdf > 0)) return std::nullopt;
        return s;
    }

    float pdf_li(Vec3, Vec3, Vec3) const override { return 0; }
    float pdf_escaped(Vec3 ref, Vec3 w, Vec3 n) const override {
        const Shares shares = shares_at(ref, n);
        float pdf = (1 - shares.portal - shares.cosine - shares.facing) * m_map->pdf(w);
        if (shares.cosine > 0) pdf += shares.cosine * std::max(0.0f, dot(w, n)) * inv_pi;
        if (shares.facing > 0) pdf += shares.facing * m_map->pdf_facing(n, w);
        if (shares.portal > 0) pdf += shares.portal * m_portals.pdf(ref, w);
        return pdf;
    }
    Rgb escaped_radiance(Vec3 w) const override { return m_map->radiance(w); }

    /// What enters the scene's sphere: the mean radiance L from every direction through a disc
    /// of its radius, 4π L A; with portals, what enters through them, at most π L A each.
    float power() const override {
        return m_map->mean_luminance() *
               (m_portals.empty() ? 4 * pi * disc_area(m_scene) : pi * m_portals.total_area());
    }
    /// A uniform world gives π L; an image at most all its light from one direction, 4π L.
    float importance(Vec3, Vec3) const override {
        return m_map->mean_luminance() * (m_map->is_uniform() ? pi : 4 * pi);
    }

    /// A direction by the map, or (half of the time, where the targets found openings) by the
    /// directions that reach what the camera sees; a start on the disc, aimed by the targets.
    std::optional<EmissionSample> sample_emission(Vec2 u_position, Vec2 u_direction) const override {
        if (!m_portals.empty()) return sample_emission_through_portals(u_position, u_direction);
        const float aimed_share = m_aimed ? 0.5f : 0.0f;
        EmissionSample s;
        if (u_direction.x < aimed_share) {
            s.d = m_aimed->sample({u_direction.x / aimed_share, u_direction.y}).d;
        } else {
            const float rest = std::min((u_direction.x - aimed_share) / (1 - aimed_share), 0x1.fffffep-1f);
            const std::optional<EnvironmentMap::Sample> sample = m_map->sample({rest, u_direction.y});
            if (!sample) return std::nullopt;
            s.d = -sample->w;
        }
        const float pdf = (1 - aimed_share) * m_map->pdf(-s.d) + (m_aimed ? aimed_share * m_aimed->pdf(s.d) : 0.0f);
        if (!(pdf > 0)) return std::nullopt;
        const DistantPhotonTargets::Start start = distant_photon_start(m_scene, m_targets, s.d, u_position);
        s.p = start.p;
        s.power = start.pdf > 0 ? m_map->radiance(-s.d) / (pdf * start.pdf) : Rgb{};
        return s;
    }

    EmissionPoint sample_emission_point(Vec2) const override { return {}; }
    Rgb emitted_intensity(const EmissionPoint&, Vec3) const override { return {}; }

    /// No place to bound: pixel reuse follows the shadow rays' directions (Light::bounds()).
    BoundingSphere bounds() const override { return {}; }

private:
    /// How sample_li divides its samples at `ref` (normal `n`): through portals, cosine-weighted,
    /// by the image's light times the cosine, and the rest by the map alone.
    struct Shares {
        float portal = 0, cosine = 0, facing = 0;
    };
    Shares shares_at(Vec3 ref, Vec3 n) const {
        // Through a window the cosine adds nothing the portals do not: portals and the map
        // (which finds a bright sun in an image) share the samples.
        if (m_portals.seen_from_inside(ref)) return {m_map->is_uniform() ? 0.75f : 0.5f, 0.0f, 0.0f};
        if (!(length2(n) > 0)) return {};
        if (m_map->is_uniform()) return {0.0f, 0.75f, 0.0f};
        // An image: half by its light alone, 45% facing the normal, a little cosine: measured
        // on outdoor_hdri's courtyard, per pixel against the reference, 4.8%; 5.0% with 35% by
        // the light alone, 6.6% with 10%, and 7.3% without the facing samples.
        return {0.0f, 0.05f, 0.45f};
    }

    /// A point uniformly on the portals, a direction into the room through it cosine-weighted
    /// about the portal's normal half of the time, else by the map (the other way: a photon
    /// without power).
    std::optional<EmissionSample> sample_emission_through_portals(Vec2 u_position, Vec2 u_direction) const {
        const auto [p, portal_n] = m_portals.uniform_point(u_position);
        EmissionSample s;
        if (u_direction.x < 0.5f) {
            s.d = OrthonormalBasis::from_normal(portal_n).to_world(
                sample_cosine_hemisphere({u_direction.x * 2, u_direction.y}));
        } else {
            const std::optional<EnvironmentMap::Sample> sample =
                m_map->sample({std::min((u_direction.x - 0.5f) * 2, 0x1.fffffep-1f), u_direction.y});
            if (!sample) return std::nullopt;
            s.d = -sample->w;
        }
        const float cos_in = dot(s.d, portal_n);
        const float pdf = 0.5f * std::max(0.0f, cos_in) * inv_pi + 0.5f * m_map->pdf(-s.d);
        s.p = origin_outside(m_scene, p, s.d);
        // L cos / (pdf_position pdf_direction), pdf_position = 1 / total area.
        s.power = cos_in > 0 && pdf > 0 ? m_map->radiance(-s.d) * (cos_in * m_portals.total_area() / pdf) : Rgb{};
        return s;
    }

    std::shared_ptr<const EnvironmentMap> m_map;
    BoundingSphere m_scene;
    Portals m_portals;
    const DistantPhotonTargets* m_targets;
    std::optional<AimedDirections> m_aimed;  // without portals, where the targets found openings
};

}  // namespace

std::unique_ptr<Light> make_sun_light(const SunLightDesc& desc, Vec3 direction, const BoundingSphere& scene,
                                      const std::vector<PortalDesc>& portals, const DistantPhotonTargets* targets) {
    return std::make_unique<SunLight>(desc, direction, scene, portals, targets);
}

std::unique_ptr<Light> make_world_light(const WorldDesc& desc, const BoundingSphere& scene,
                                        const std::vector<PortalDesc>& portals, const DistantPhotonTargets* targets) {
    return std::make_unique<WorldLight>(desc, scene, portals, targets);
}

}  // namespace steadylight
