// A ray: origin, unit direction and the far end of the segment it covers.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "steadylight/base/vec.h"

namespace steadylight {

constexpr float infinity = std::numeric_limits<float>::infinity();

struct Ray {
    Vec3 o;
    Vec3 d;
    float tmax = infinity;
};

/// The scale of the offset that lifts a new ray off the surface it starts on, so it does not
/// hit that surface again through float rounding; it grows with the distance from the origin.
inline float ray_epsilon(Vec3 p) { return 1e-4f * (1.0f + std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)})); }

/// A ray leaving surface point `p` with geometric normal `ng` in direction `d`.
inline Ray spawn_ray(Vec3 p, Vec3 ng, Vec3 d) {
    const float side = dot(d, ng) >= 0 ? 1.0f : -1.0f;
    return {p + ng * (side * ray_epsilon(p)), d, infinity};
}

/// A shadow ray from surface point `p` to a point `target` (on a light), stopping short of the
/// target by the same epsilon, so that the light's own surface never occludes it.
inline Ray spawn_ray_to(Vec3 p, Vec3 ng, Vec3 target) {
    Ray ray = spawn_ray(p, ng, target - p);
    // Aim from the lifted origin: aiming from p would make the ray miss the target's distance.
    ray.d = target - ray.o;
    const float distance = length(ray.d);
    ray.d = ray.d / distance;
    ray.tmax = std::max(0.0f, distance - ray_epsilon(target));
    return ray;
}

}  // namespace steadylight
