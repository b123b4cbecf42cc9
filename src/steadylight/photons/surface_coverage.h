// How much of a density estimate's disc lies on the surface: the correction for the boundary
// bias of photon density estimates (Jensen 2001 §7.3 names it; docs/notes/truth-density-estimate.md measures it).
// An estimate divides the power of the photons it finds by the disc's area, pi r^2. Near an edge
// (a wall meeting the floor, a table's rim, a thin leg) part of that disc is not on the surface,
// no photon can land there, and the estimate comes out low: at the edge itself by half. Final
// gather rays land near edges more often than their share of the surfaces (a point near a
// wall sees that wall's edges close by), so the gathered light came out about 1% dark
// (docs/notes/truth-density-estimate.md).
//
// The disc is probed by rays: 16 points spread over it (two rings of eight, stratified by area,
// turned by a per-estimate angle so that straight edges are not met at one angle only). A point
// counts when the surface reaches it from the centre: a ray just above the tangent plane from
// the centre towards it meets nothing (or a surface that faces the same way, where the surface
// curves up), and a ray down from it meets, within the disc's radius, a surface facing the
// centre's way (where it curves down, a sphere). What the photons' normal filter counts (normals
// within 60 degrees) is what the probes count.
//
// The same test tells whether a photon lies on the surface the estimate is for (`reaches`):
// photons in the cells whose probe missed, and photons in front of the disc's plane (checked by a
// ray from the lifted centre), count only if it passes. Without it the light trapped inside a
// lamp's closed housing against a wall, or hung just under the ceiling, leaked into the
// estimates beside it (docs/notes/truth-lamp-housings.md).
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>

#include "steadylight/base/ray.h"
#include "steadylight/shading/frame_context.h"

namespace steadylight {

/// How far off the surface, over a disc's radius, the probes of its coverage start.
constexpr float coverage_lift = 0.02f;
/// The least height off the surface they start at: well above the ray epsilon.
inline float coverage_min_lift(Vec3 p) { return 10 * ray_epsilon(p); }
/// How far from the centre p of a density estimate's disc of radius r the rays of its probes
/// reach (they start at most max(coverage_lift r, coverage_min_lift) above the disc and look at
/// most r below it), and so do those of SurfaceCoverage::reaches for points within the disc.
inline float coverage_probe_extent(Vec3 p, float r) { return 2 * r + 2 * coverage_min_lift(p); }

/// Which cells of a density estimate's disc the surface under its centre reaches, one probe per
/// cell: two rings of equal area, eight sectors each, in the disc's frame
/// (OrthonormalBasis::from_normal of its normal), the sectors turned by `turn` (in sectors) and the outer
/// ring's by half a sector more. Sector j of a ring is centred on its probe's angle.
struct DiscProbes {
    static constexpr int rings = 2, sectors = 8;
    uint16_t reached = 0xffff;  // bit ring * sectors + sector
    float turn = 0;

    float share() const { return float(std::popcount(reached)) / (rings * sectors); }
    /// The angle, in the disc's frame, at which the probe of cell (ring, sector) lies: the
    /// middle of its sector, turned by `turn` sectors, the outer ring half a sector further.
    float angle(int ring, int sector) const { return 2 * pi * (float(sector) + turn + 0.5f * float(ring)) / sectors; }
    /// Whether the probe of the cell holding the disc's point (x, y), in its frame, reached it;
    /// `radius2` is the disc's squared radius.
    bool reached_cell(float x, float y, float radius2) const {
        const int ring = x * x + y * y < radius2 / rings ? 0 : 1;
        const float at = std::atan2(y, x) * (sectors / (2 * pi)) - turn - 0.5f * float(ring);
        const int sector = ((int(std::floor(at + 0.5f)) % sectors) + sectors) % sectors;
        return (reached >> (ring * sectors + sector)) & 1;
    }
};

/// How a density estimate's disc lies on the surface under its centre (surface_coverage() makes it).
struct SurfaceCoverage {
    /// The probes of the disc of radius `radius` around `p`, in the plane of normal `n`: which
    /// of its cells the surface under p reaches, seen from `lift` above the plane (a step lower
    /// than that does not stop it), a surface at most `reach` below the plane counting as on it;
    /// `seed` varies where they probe.
    std::function<DiscProbes(Vec3 p, Vec3 n, float radius, float lift, float reach, uint64_t seed)> probes;
    /// Whether the surface under p reaches q (taken onto the disc's plane, or, in front of it,
    /// seen from the centre), `radius` being the disc's: a photon there lies on the surface the
    /// estimate is for, not behind a wall that rises from it (the inside of a lamp's closed
    /// housing against a wall) or on another surface just in front of it (a housing's top hung
    /// under the ceiling).
    std::function<bool(Vec3 p, Vec3 n, float radius, Vec3 q)> reaches;

    explicit operator bool() const { return bool(probes); }
};

/// The coverage of discs on the surfaces `visibility` sees at `context`'s frame. The returned
/// functions keep a copy of the frame's placement (FrameState) and refer to `context`'s scene and
/// ray tracer, which must outlive them, not to the context itself: a segment's precomputed
/// irradiance keeps its coverage for its look-ups after the frame it was made at is gone.
SurfaceCoverage surface_coverage(const FrameContext& context, Visibility visibility);

}  // namespace steadylight
