// Lights: emissive objects (area lights), point and spot lights, and lights from far away (suns
// and the world), and the LightSet that picks one in proportion to its power for next-event
// estimation. Built per frame, since emissive
// objects may move and lights may be switched or dimmed (FrameState's emission and intensity).
// Interface here, one file per kind of light.
#pragma once

#include <cmath>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "steadylight/base/bounding_sphere.h"
#include "steadylight/scene/scene.h"

namespace steadylight {

/// A point on a light chosen for a shading point `ref`.
struct LightSample {
    Vec3 p;              // on the light (lights from far away: a point along wi beyond the scene)
    Vec3 n;              // the light's normal at p (zero for point lights and lights from far away)
    Vec3 wi;             // unit direction from ref towards p
    float distance = 0;  // infinity for lights from far away
    Rgb Li;              // radiance arriving at ref along -wi (for point lights: intensity / distance^2)
    float pdf = 0;       // solid angle at ref (point lights: 1), times the probability of the light
    bool is_delta = false;
};

/// A photon's start: where it leaves the light, which way, and its power up to the 1/N that
/// spreads the light's power over the N photons emitted.
struct EmissionSample {
    Vec3 p;
    Vec3 n;                      // the emitting surface's normal on the side the photon leaves (zero for point lights)
    Vec3 d;                      // unit direction
    Rgb power;                   // Le cos / (pdf_position pdf_direction), divided by the light's selection probability
    bool from_far_away = false;  // from a sun or the world (LightSet::sample_emission sets it)
};

/// Where a photon leaves a light before its direction is chosen (for photons aimed at targets).
struct EmissionPoint {
    size_t light = 0;  // index in the LightSet
    Vec3 p;
    Vec3 n;         // the emitting surface's front normal (zero for point lights)
    float pdf = 0;  // by area on the light (1 for point lights), times the light's selection probability
};

class Light {
public:
    virtual ~Light() = default;
    /// Samples a point as seen from `ref`; pdf in solid angle, not counting light selection.
    /// `n`, the surface normal at ref (zero where there is none), lets light from every
    /// direction favour the hemisphere it faces.
    virtual std::optional<LightSample> sample_li(Vec3 ref, Vec2 u, Vec3 n) const = 0;
    /// Whether sample_li reads its `n`: light from every direction does, a light with a place or
    /// a single direction does not.
    virtual bool samples_by_normal() const { return false; }
    /// The solid-angle pdf sample_li would give for reaching `p` (normal `n`) from `ref`.
    virtual float pdf_li(Vec3 ref, Vec3 p, Vec3 n) const = 0;
    /// What a ray leaving the scene along unit `w` sees of this light (lights from far away)...
    virtual Rgb escaped_radiance(Vec3 /*w*/) const { return {}; }
    /// ...and the solid-angle pdf sample_li gives `w` for a point `ref` of normal `n`.
    virtual float pdf_escaped(Vec3 /*ref*/, Vec3 /*w*/, Vec3 /*n*/) const { return 0; }
    /// Total emitted power (luminance of W), used to choose lights.
    virtual float power() const = 0;
    /// \brief An upper estimate of the luminance of irradiance the light could give a surface
    /// at `ref` with normal `n`, unoccluded (bounding-sphere cone bounds, as pbrt-v4's
    /// LightBounds::Importance). Zero only where the light cannot reach that surface.
    virtual float importance(Vec3 ref, Vec3 n) const = 0;
    /// Samples a photon start; pdf-weighted as EmissionSample says (without light selection).
    virtual std::optional<EmissionSample> sample_emission(Vec2 u_position, Vec2 u_direction) const = 0;
    /// Samples where a photon leaves, leaving the direction to the caller; pdf without selection.
    virtual EmissionPoint sample_emission_point(Vec2 u) const = 0;
    /// \brief Radiant intensity leaving `at` towards unit `d`, per unit of `at`'s pdf measure:
    /// Le |cos| on an emitting side of an area light (zero on the other), a lamp's intensity.
    virtual Rgb emitted_intensity(const EmissionPoint& at, Vec3 d) const = 0;
    /// A sphere holding every point the light emits from (a point light's has radius 0). Lights
    /// from far away have none (an empty sphere): their shadow rays have no end, and pixel reuse
    /// follows the directions a pixel's shadow rays took towards them instead (PixelTrace).
    virtual BoundingSphere bounds() const = 0;
};

/// Area light over the world-space surface of emissive object `object` at this frame, with the
/// frame's emission.
std::unique_ptr<Light> make_area_light(const Scene& scene, const FrameState& frame, int object);
/// A point or spot light where, and as bright as, `pose` (the lamp's at the frame) says.
std::unique_ptr<Light> make_point_light(const PointLightDesc& desc, const PointLightPose& pose);
/// A sun whose light travels `direction` (the sun's at the frame), and the world, whose photons
/// cover `scene` (Scene::bounds()), or enter through `portals` when there are any.
/// Without portals, `targets` (when not null) aims them (scene/distant_photon_targets.h).
std::unique_ptr<Light> make_sun_light(const SunLightDesc& desc, Vec3 direction, const BoundingSphere& scene,
                                      const std::vector<PortalDesc>& portals, const DistantPhotonTargets* targets);
std::unique_ptr<Light> make_world_light(const WorldDesc& desc, const BoundingSphere& scene,
                                        const std::vector<PortalDesc>& portals, const DistantPhotonTargets* targets);

/// The shadow ray from surface point `p` (geometric normal `ng`) towards a sampled light: to its
/// point `to`, or open-ended along direction `to` towards a light from far away (`distant`).
inline Ray shadow_ray(Vec3 p, Vec3 ng, Vec3 to, bool distant) {
    return distant ? spawn_ray(p, ng, to) : spawn_ray_to(p, ng, to);
}
/// The shadow ray towards light sample `light`.
inline Ray shadow_ray(const LightSample& light, Vec3 p, Vec3 ng) {
    const bool distant = std::isinf(light.distance);
    return shadow_ray(p, ng, distant ? light.wi : light.p, distant);
}

/// The lights whose photons a photon pass emits apart (docs/localized.md, "Lights that move"):
/// those that stand still through the animation, and the lamps and suns that move, whose photons
/// are traced afresh every frame.
enum class PhotonGroup { still, moving };

/// How the photon paths of a map split between the groups, in proportion to their power, so that
/// every photon carries the same power: paths [0, still) leave the still lights, [still, total)
/// the moving ones. A group with power gets at least one path.
struct PhotonSplit {
    long still = 0, total = 0;

    long count(PhotonGroup group) const { return group == PhotonGroup::still ? still : total - still; }
    PhotonGroup group_of(long path) const { return path < still ? PhotonGroup::still : PhotonGroup::moving; }
};

class LightSet {
public:
    /// The lights that are on at `frame`; a light whose emission or intensity is black at the
    /// frame is left out (switched off).
    LightSet(const Scene& scene, const FrameState& frame);

    bool empty() const { return m_lights.empty(); }
    /// Picks a light with `u_select` and samples it (for a point of normal `n`, when known:
    /// Light::sample_li); the pdf includes the choice.
    std::optional<LightSample> sample(Vec3 ref, float u_select, Vec2 u, Vec3 n = {}) const;
    /// \brief Picks a light with u.x and samples it with (the remainder of u.x within the
    /// light's share, u.y); the pdf is sample()'s. Stratified u then stratify each light's
    /// area as well as the choice.
    std::optional<LightSample> sample_reusing(Vec3 ref, Vec2 u) const;
    /// \brief sample_reusing() with lights chosen by their importance() at `ref` (normal `n`),
    /// mixed with the power choice so that every light keeps some chance; the pdf includes that
    /// choice, which pdf_emitter() does not know (its caller has no normal), so this is for
    /// estimators that do not weigh against BSDF sampling. Above `max_lights_by_importance`
    /// lights, the power choice.
    std::optional<LightSample> sample_reusing(Vec3 ref, Vec3 n, Vec2 u) const;
    static constexpr size_t max_lights_by_importance = 32;
    /// Picks a light in proportion to power with `u_select` and samples a photon start from it;
    /// with `group`, among that group's lights only.
    std::optional<EmissionSample> sample_emission(float u_select, Vec2 u_position, Vec2 u_direction) const;
    std::optional<EmissionSample> sample_emission(PhotonGroup group, float u_select, Vec2 u_position,
                                                  Vec2 u_direction) const;
    /// \brief Picks a light of `group` in proportion to power with `u_select` and a point on it;
    /// the photon's direction is the caller's (power = emitted_intensity / (pdf of the point and
    /// direction)).
    std::optional<EmissionPoint> sample_emission_point(PhotonGroup group, float u_select, Vec2 u_position) const;
    /// `paths` photon paths split between the groups by their power.
    PhotonSplit split(long paths) const;
    /// True when some light that is on moves (PhotonGroup::moving).
    bool has_moving() const { return !m_group_lights[1].empty(); }
    Rgb emitted_intensity(const EmissionPoint& at, Vec3 d) const {
        return m_lights[at.light]->emitted_intensity(at, d);
    }
    /// Every light's bounds(), in the set's order (empty for lights from far away).
    std::vector<BoundingSphere> bounds() const;
    /// The pdf sample() gives for reaching point p (normal n) on emissive object `object`.
    float pdf_emitter(int object, Vec3 ref, Vec3 p, Vec3 n) const;
    /// What a ray leaving the scene along unit `w` sees: the lights from far away.
    Rgb escaped_radiance(Vec3 w) const;
    /// escaped_radiance() for a ray sampled with solid-angle pdf `bsdf_pdf` at point `ref` of
    /// normal `n`: each light's part weighted by the power heuristic against sample() choosing
    /// that light and sampling `w` from it.
    Rgb escaped_radiance(Vec3 ref, Vec3 w, Vec3 n, float bsdf_pdf) const;

private:
    std::vector<std::unique_ptr<Light>> m_lights;
    std::vector<float> m_cdf;  // over m_lights, by power
    // Per photon group: its lights (indices into m_lights) and a cdf over them by power.
    std::vector<size_t> m_group_lights[2];
    std::vector<float> m_group_cdf[2];
    float m_group_power[2] = {0, 0};
    std::vector<int> m_light_of_object;  // object -> index in m_lights, or -1
    size_t m_first_distant = 0;          // the lights from far away come last

    /// The light `u_select` picks and the probability of picking it.
    std::pair<size_t, float> choose(float u_select) const;
    /// The light of `group` that `u_select` picks and the probability of picking it within the group.
    std::pair<size_t, float> choose(PhotonGroup group, float u_select) const;
    /// A photon start from light `i`, picked with probability `p_select`.
    std::optional<EmissionSample> emission_from(size_t i, float p_select, Vec2 u_position, Vec2 u_direction) const;
    /// Samples light `i`, chosen with probability `p_select` by u.x in [lo, lo + p_select): the
    /// rest of u.x, rescaled to [0,1), and u.y place the point on it; the pdf includes the choice.
    std::optional<LightSample> sample_chosen(size_t i, float lo, float p_select, Vec3 ref, Vec3 n, Vec2 u) const;
};

/// \brief An upper estimate of `intensity` cos_ref cos_light / distance^2 over a light inside the
/// sphere (`center`, `radius`), seen from `ref` with normal `n`: each cosine tilted towards its
/// normal by the sphere's angular radius. `light_n` zero: the light shines every way.
float importance_bound(float intensity, Vec3 ref, Vec3 n, Vec3 center, float radius, Vec3 light_n);

/// Converts an area-measure pdf at `p` (normal `n`) into solid angle as seen from `ref`.
float area_to_solid_angle(float pdf_area, Vec3 ref, Vec3 p, Vec3 n);

}  // namespace steadylight
