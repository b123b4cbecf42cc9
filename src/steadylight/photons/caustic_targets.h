// Caustic photons aimed at the objects that make caustics (Jensen 2001, §5.4.1, projection
// maps, here with bounding spheres instead of a grid of directions): only a path whose first hit
// is a specular or glossy object can store a caustic photon, so photons leave each light only
// in the cones that bound those objects as seen from their starting point, each cone chosen in
// proportion to its solid angle. Then the pdf of a direction is (the number of cones holding
// it) / (the cones' total solid angle), every caustic path keeps a non-zero pdf, and a small
// glass sphere under a big light gets many times the photons of emission over the hemisphere.
// Where the cones would cover a hemisphere or more (a glossy floor under its lamp, or more than
// max_targets objects) aiming gains nothing and the light's own emission is used instead.
#pragma once

#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "steadylight/shading/frame_context.h"

namespace steadylight {

/// A direction a photon leaves in and its pdf in solid angle.
struct AimedDirection {
    Vec3 d;
    float pdf = 0;
};

class CausticTargets {
public:
    static constexpr size_t max_targets = 32;

    /// The non-diffuse objects `visibility` lets photons meet, bounded at `context.frame`.
    CausticTargets(const FrameContext& context, Visibility visibility);

    /// A direction from `p` into one target's cone, or nothing when aiming does not pay from `p`
    /// (then emit as the light does on its own).
    std::optional<AimedDirection> sample(Vec3 p, Vec2 u) const;
    /// The pdf sample() gives to direction `d` from `p` (zero where it does not aim).
    float pdf(Vec3 p, Vec3 d) const;

    /// Same targets: photons leave the lights the same way.
    bool operator==(const CausticTargets&) const = default;

private:
    struct Cone {
        Vec3 axis;
        float cos_max = -1;
        float solid_angle = 4 * pi;
    };
    using Cones = std::array<Cone, max_targets>;
    /// The targets' cones from `p` (one per target) and their total solid angle, or zero when
    /// aiming does not pay from `p`.
    float cones_from(Vec3 p, Cones& cones) const;
    /// How many of the cones hold direction `d`.
    int cones_holding(const Cones& cones, Vec3 d) const;

    std::vector<Vec3> m_centers;
    std::vector<float> m_radii;
};

/// A sphere holding the object as the frame places it (all of a mesh's vertices).
std::pair<Vec3, float> bounding_sphere(const Scene& scene, const FrameState& frame, int object);

}  // namespace steadylight
