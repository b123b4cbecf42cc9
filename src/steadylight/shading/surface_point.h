// The local geometry at a ray hit, in world space: position, normals and which object it is.
// Computed from the object-space shape and the object's placement at the frame.
#pragma once

#include <optional>

#include "steadylight/scene/scene.h"
#include "steadylight/shading/bsdf.h"
#include "steadylight/trace/ray_tracer.h"

namespace steadylight {

struct SurfacePoint {
    Vec3 p;
    Vec3 ng;  // unit geometric normal on the shape's front side (outside, or as vertex normals say)
    Vec3 ns;  // unit shading normal, in the same hemisphere as ng
    int object = -1;
};

SurfacePoint make_surface_point(const Scene& scene, const FrameState& frame, const Ray& ray, const Hit& hit);

/// A sampled scattering: the BSDF sample and the ray that continues from the surface.
struct Bounce {
    BsdfSample sample;
    Ray ray;
};

/// Samples `bsdf` at `sp` for a ray arriving along `d`, in the frame of the surface's own
/// normals (not turned towards the ray): the dielectric tells entering from leaving by the side
/// of its front, outward normal that -d lies on; the reflective BSDFs are two-sided.
std::optional<Bounce> sample_bounce(const Bsdf& bsdf, const SurfacePoint& sp, Vec3 d, Vec2 u, float u_lobe,
                                    TransportMode mode);

/// Radiance that `object`, emitting `Le` at this frame (FrameState::emission), emits from a
/// point with front normal `ng` towards direction `w`.
Rgb emitted_radiance(const ObjectDesc& object, Rgb Le, Vec3 ng, Vec3 w);

}  // namespace steadylight
