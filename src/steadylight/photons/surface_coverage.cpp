// Probing a density estimate's disc with rays (surface_coverage.h).
#include "steadylight/photons/surface_coverage.h"

#include <cmath>
#include <memory>

#include "steadylight/base/rng.h"
#include "steadylight/photons/photon.h"
#include "steadylight/shading/surface_point.h"

namespace steadylight {
namespace {

/// What the probes need, kept by the coverage's functions: the scene and the tracer by reference
/// (they outlive the frames), the frame's placement by value.
struct ProbeWorld {
    const Scene& scene;
    const RayTracer& tracer;
    FrameState frame;
    Visibility visibility;
};

/// Whether the surface met by `ray` (if any) faces `n`'s way, seen from the ray's side.
bool meets_surface_facing(const ProbeWorld& world, const Ray& ray, Vec3 n) {
    const std::optional<Hit> hit = world.tracer.intersect(ray, world.visibility);
    if (!hit) return false;
    const Vec3 ng = make_surface_point(world.scene, world.frame, ray, *hit).ng;
    return std::abs(dot(ng, n)) > same_side_cosine;  // two-sided: the side facing the ray
}

/// Whether the surface under the centre `p` (normal `n`) reaches the disc point `q`, at most
/// `reach` below the tangent plane.
bool covers(const ProbeWorld& world, Vec3 p, Vec3 n, Vec3 q, float lift, float reach) {
    const Vec3 along = q - p;
    const float distance = length(along);
    if (distance <= lift) return true;  // the centre itself is on the surface
    const Ray across{p + n * lift, along / distance, distance};
    if (world.tracer.occluded(across, world.visibility)) return meets_surface_facing(world, across, n);
    // Any surface within reach below the point counts (an occlusion ray: cheaper than finding
    // which surface, and what lies below a tangent plane faces up).
    return world.tracer.occluded({q + n * lift, -n, lift + reach}, world.visibility);
}

/// How far off the surface `reaches` starts: a little of the disc.
float lift_for(Vec3 p, float radius) { return std::max(coverage_lift * radius, coverage_min_lift(p)); }

}  // namespace

SurfaceCoverage surface_coverage(const FrameContext& context, Visibility visibility) {
    // Light passes through glass, smooth or rough, and photons land on what lies behind it (the
    // floor under a glass block): the probes look through it. Stopped by it, they left out of the
    // disc the floor beyond a glass block whose photons the estimate still read (blender_glass's
    // floor around its blue block: L_t's change 2 to 5 times the true one).
    const auto world = std::make_shared<const ProbeWorld>(
        ProbeWorld{context.scene, context.tracer, context.frame, opaque_only(visibility)});
    SurfaceCoverage coverage;
    coverage.probes = [world](Vec3 p, Vec3 n, float radius, float lift_above, float reach, uint64_t seed) {
        const OrthonormalBasis basis = OrthonormalBasis::from_normal(n);
        const float lift = std::max(lift_above, coverage_min_lift(p));
        const uint64_t bits = hash_ids(seed);
        DiscProbes probes;
        probes.reached = 0;
        probes.turn = float(bits & 0xffffff) * 0x1p-24f;
        const float jitter = float((bits >> 24) & 0xffffff) * 0x1p-24f;
        for (int ring = 0; ring < DiscProbes::rings; ++ring) {
            // Each ring holds an equal share of the disc's area; the point sits at a jittered
            // area fraction within its share.
            const float r = radius * std::sqrt((float(ring) + jitter) / DiscProbes::rings);
            for (int j = 0; j < DiscProbes::sectors; ++j) {
                const float phi = probes.angle(ring, j);
                const Vec3 q = p + basis.to_world({r * std::cos(phi), r * std::sin(phi), 0});
                if (covers(*world, p, n, q, lift, reach))
                    probes.reached |= uint16_t(1u << (ring * DiscProbes::sectors + j));
            }
        }
        return probes;
    };
    coverage.reaches = [world](Vec3 p, Vec3 n, float radius, Vec3 q) {
        const float lift = lift_for(p, radius), height = dot(q - p, n);
        // In front of the disc's plane (another surface a little off it, such as a lamp's
        // housing hung just under the ceiling, or a concave one curving up): seen from the centre
        // along a path that keeps in front of both, or not on this surface.
        if (height > lift) {
            const Vec3 along = q - p;
            const float distance = length(along);
            return !world->tracer.occluded({p + n * lift, along / distance, distance}, world->visibility);
        }
        return covers(*world, p, n, q - n * height, lift, radius);
    };
    return coverage;
}

}  // namespace steadylight
