// Light seen in flat mirrors, sampled at glossy surfaces (docs/materials.md, "The photon method": light in mirrors).
// A glossy surface takes direct light by light sampling, but the light it sees reflected in a
// mirror could only be found by its sampled bounce: a small light's mirror image, found by a few
// rays out of a pixel's 64, came out as sparkles on a glossy floor beside a mirror. In a flat
// mirror the image of a light is a light too: sampling the light as seen from the shading
// point's mirror image gives the same point, pdf and radiance as sampling that image from the
// point. So each glossy point also samples every static flat mirror's image of the lights, and
// the sampled bounce no longer counts emission reached by one reflection in such a mirror (the
// path glossy -> mirror -> light is counted once, here). Moving mirrors keep the sampled bounce
// alone: their images would move under pixels that the localized method reuses.
#pragma once

#include <vector>

#include "steadylight/base/vec.h"
#include "steadylight/scene/scene.h"

namespace steadylight {

/// A static mirror whose triangles all lie in one plane, with vertex normals (if any) along the
/// plane's: world-space point and unit normal at the frame.
struct MirrorPlane {
    int object = -1;
    Vec3 point;
    Vec3 normal;
};

/// The static objects of `scene` with a mirror material that are flat, placed at `frame`.
std::vector<MirrorPlane> flat_mirrors(const Scene& scene, const FrameState& frame);

}  // namespace steadylight
