// How much of a density estimate's disc lies on the surface: the correction for the boundary
// bias of photon density estimates (Jensen 2001 §7.3 names it; docs/truth-suite.md measures it).
// An estimate divides the power of the photons it finds by the disc's area, pi r^2. Near an edge
// (a wall meeting the floor, a table's rim, a thin leg) part of that disc is not on the surface,
// no photon can land there, and the estimate comes out low: at the edge itself by half. Final
// gather rays land near edges more often than their share of the surfaces (a point near a
// wall sees that wall's edges close by), so the gathered light came out about 1% dark
// (docs/truth-suite.md).
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
// estimates beside it (docs/truth-suite.md, "Light trapped in lamp housings").
#pragma once

#include "steadylight/photons/photon_map.h"
#include "steadylight/shading/frame_context.h"

namespace steadylight {

/// The coverage of discs on the surfaces `visibility` sees at `context`'s frame. The returned
/// functions keep a copy of the frame's placement (FrameState) and refer to `context`'s scene and
/// ray tracer, which must outlive them, not to the context itself: a segment's precomputed
/// irradiance keeps its coverage for its look-ups after the frame it was made at is gone.
SurfaceCoverage surface_coverage(const FrameContext& context, Visibility visibility);

}  // namespace steadylight
