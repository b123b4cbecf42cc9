// Probing a density estimate's disc with rays (surface_coverage.h).
#include "steadylight/photons/surface_coverage.h"

#include <cmath>

#include "steadylight/base/rng.h"
#include "steadylight/shading/surface_point.h"

namespace steadylight {
namespace {

constexpr int rings = 2, directions = 8;
constexpr float same_side_cosine = 0.5f;  // as the photons' normal filter (photon.h, same_side)

/// Whether the surface met by `ray` (if any) faces `n`'s way, seen from the ray's side.
bool meets_surface_facing(const FrameContext& context, const Ray& ray, Vec3 n, Visibility visibility) {
    const std::optional<Hit> hit = context.tracer.intersect(ray, visibility);
    if (!hit) return false;
    const Vec3 ng = make_surface_point(context.scene, context.frame, ray, *hit).ng;
    return std::abs(dot(ng, n)) > same_side_cosine;  // two-sided: the side facing the ray
}

/// Whether the surface under the centre `p` (normal `n`) reaches the disc point `q`, at most
/// `reach` below the tangent plane.
bool covers(const FrameContext& context, Visibility visibility, Vec3 p, Vec3 n, Vec3 q, float lift, float reach) {
    const Vec3 along = q - p;
    const float distance = length(along);
    if (distance <= lift) return true;  // the centre itself is on the surface
    const Ray across{p + n * lift, along / distance, distance};
    if (context.tracer.occluded(across, visibility)) return meets_surface_facing(context, across, n, visibility);
    // Any surface within reach below the point counts (an occlusion ray: cheaper than finding
    // which surface, and what lies below a tangent plane faces up).
    return context.tracer.occluded({q + n * lift, -n, lift + reach}, visibility);
}

}  // namespace

SurfaceCoverage surface_coverage(const FrameContext& context, Visibility visibility) {
    return [&context, visibility](Vec3 p, Vec3 n, float radius, uint64_t seed) {
        const Frame frame = Frame::from_normal(n);
        // Lifted off the surface by a little of the disc, well above the ray epsilon.
        const float lift = std::max(0.02f * radius, 10 * ray_epsilon(p));
        const uint64_t bits = hash_ids(seed);
        const float turn = float(bits & 0xffffff) * 0x1p-24f, jitter = float((bits >> 24) & 0xffffff) * 0x1p-24f;
        int covered = 0;
        for (int ring = 0; ring < rings; ++ring) {
            // Each ring holds an equal share of the disc's area; the point sits at a jittered
            // area fraction within its share.
            const float r = radius * std::sqrt((float(ring) + jitter) / rings);
            for (int j = 0; j < directions; ++j) {
                const float phi = 2 * pi * (float(j) + turn + 0.5f * float(ring)) / directions;
                const Vec3 q = p + frame.to_world({r * std::cos(phi), r * std::sin(phi), 0});
                covered += covers(context, visibility, p, n, q, lift, radius);
            }
        }
        return float(covered) / (rings * directions);
    };
}

}  // namespace steadylight
