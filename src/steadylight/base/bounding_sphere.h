// Bounding spheres and the conservative tests pixel reuse (passes/pixel_reuse.h) and the ray
// tracer's instance queries make with them: whether a sphere may meet the segments between two
// others, or a ray. Conservative means a "no" is certain and a "yes" only possible.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "steadylight/base/vec.h"

namespace steadylight {

struct BoundingSphere {
    Vec3 center;
    float radius = -1;  // negative: empty

    bool empty() const { return radius < 0; }

    /// The sphere about the box [lo, hi] (empty when lo > hi on some axis).
    static BoundingSphere of_box(Vec3 lo, Vec3 hi) {
        if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) return {};
        return {(lo + hi) * 0.5f, length(hi - lo) * 0.5f};
    }
};

/// Whether `s` may meet a segment from a point of sphere `from` to a point of sphere `to`. Every
/// such segment lies in the convex hull of the two spheres, the union over t in [0, 1] of the
/// spheres about lerp(centres, t) with radius lerp(radii, t). The distance from s's centre to
/// sphere t, gap(t) = |c - x(t)| - r(t), is convex in t; its least value over [0, 1] is at the
/// point where its derivative vanishes, clamped to [0, 1]. With a the centre's distance along
/// the centres' axis (length L), h its distance off it and k = (r_to - r_from) / L the radii's
/// slope, gap(tau) = sqrt((a - tau)^2 + h^2) - r_from - k tau for tau = t L, whose derivative
/// vanishes where tau - a = k h / sqrt(1 - k^2); for |k| >= 1 gap is monotonic, least at an end.
/// `slack` widens the test (rounding, ray offsets).
inline bool may_meet_segments(const BoundingSphere& s, const BoundingSphere& from, const BoundingSphere& to,
                              float slack) {
    if (s.empty() || from.empty() || to.empty()) return false;
    // First the capsule of the larger radius about the centres' segment, which holds the hull:
    // most spheres are clear of it, and it costs one distance.
    const Vec3 along = to.center - from.center, to_s = s.center - from.center;
    const float along2 = length2(along), s_along = dot(to_s, along);
    const float t_nearest = std::clamp(s_along / std::max(along2, 1e-30f), 0.0f, 1.0f);
    if (length(s.center - (from.center + along * t_nearest)) > s.radius + std::max(from.radius, to.radius) + slack)
        return false;
    const auto gap = [&](float t) {
        return length(s.center - lerp(from.center, to.center, t)) - (from.radius + (to.radius - from.radius) * t);
    };
    float t_least = 0;
    if (along2 > 0) {
        const float L = std::sqrt(along2), a = s_along / L;
        const float h = length(to_s - along * (s_along / along2));
        const float k = (to.radius - from.radius) / L;
        if (std::abs(k) < 1) t_least = std::clamp((a + k * h / std::sqrt(1 - k * k)) / L, 0.0f, 1.0f);
    }
    const float least = std::min({gap(0), gap(1), gap(t_least)});
    return least <= s.radius + slack;
}

/// Whether `s` may meet the ray o + t d for t in [0, tmax]: the ray's point nearest the centre,
/// widened by a margin far beyond float rounding (two ten-thousandths of the distances involved,
/// measured along their largest axis). No square root: the ray tracer asks it of many rays.
inline bool may_meet_ray(const BoundingSphere& s, Vec3 o, Vec3 d, float tmax) {
    if (s.empty()) return false;
    const Vec3 to_centre = s.center - o;
    const float t = std::clamp(dot(to_centre, d) / std::max(length2(d), 1e-30f), 0.0f, tmax);
    const auto largest = [](Vec3 v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); };
    const float reach = s.radius + 2e-4f * (1 + s.radius + largest(to_centre) + largest(o));
    return length2(d * t - to_centre) <= reach * reach;
}

}  // namespace steadylight
