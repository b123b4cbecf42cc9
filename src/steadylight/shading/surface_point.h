// The local geometry at a ray hit, in world space: position, normals and which object it is.
// Computed from the object-space shape and the object's placement at the frame.
#pragma once

#include <optional>

#include "steadylight/scene/mesh_attributes.h"
#include "steadylight/scene/scene.h"
#include "steadylight/shading/bsdf.h"
#include "steadylight/shading/frame_context.h"
#include "steadylight/trace/ray_tracer.h"

namespace steadylight {

struct SurfacePoint {
    Vec3 p;
    Vec3 ng;  // unit geometric normal on the shape's front side (outside, or as vertex normals say)
    Vec3 ns;  // unit interpolated normal, in the same hemisphere as ng: photons and cache records use it
    Vec3 nm;  // unit normal of the BSDF's frame: ns bent by the material's normal map (ns without one)
    int object = -1;
    SurfaceAttributes attributes;  // texture coordinates and vertex colour (triangle meshes)
};

/// The surface where `ray` met `hit`, with the material's normal map applied to `nm`.
SurfacePoint make_surface_point(const Scene& scene, const FrameState& frame, const Ray& ray, const Hit& hit);

/// The BSDF at a surface point: its material's shared one, or, when textures or vertex colours
/// vary the material, one made for the point. Movable, not copyable.
class SurfaceBsdf {
public:
    explicit SurfaceBsdf(const Bsdf& shared) : m_bsdf(&shared) {}
    explicit SurfaceBsdf(std::unique_ptr<Bsdf> own) : m_own(std::move(own)), m_bsdf(m_own.get()) {}
    const Bsdf& operator*() const { return *m_bsdf; }
    const Bsdf* operator->() const { return m_bsdf; }

private:
    std::unique_ptr<Bsdf> m_own;
    const Bsdf* m_bsdf;
};

SurfaceBsdf bsdf_at(const FrameContext& context, const SurfacePoint& sp);

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

/// \brief Beer-Lambert transmittance of the segment a ray (direction `d`) travelled to its hit
/// `sp` at distance `distance`: exp(-sigma_a distance) when it arrives at the back of an
/// absorbing dielectric, that is, it travelled inside that object's volume; white otherwise.
/// Every tracer applies it at every hit, so that the whole distance travelled inside glass is
/// absorbed, whichever surface the segment began on (its limits: docs/materials.md, "Glass").
Rgb volume_transmittance(const FrameContext& context, const SurfacePoint& sp, Vec3 d, float distance);

/// Radiance that the surface at `sp` emits towards `w` at this frame: its object's emission
/// tinted by its material's emissive texture.
Rgb emitted_radiance_at(const FrameContext& context, const SurfacePoint& sp, Vec3 w);

/// Radiance that `object`, emitting `Le` at this frame (FrameState::emission), emits from a
/// point with front normal `ng` towards direction `w`.
Rgb emitted_radiance(const ObjectDesc& object, Rgb Le, Vec3 ng, Vec3 w);

}  // namespace steadylight
