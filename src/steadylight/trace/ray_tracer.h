// RayTracer: the renderer's only door to Embree (with embree_device.h). Static objects are baked
// into world space in one scene built once at high quality; dynamic objects are built once each
// in object space and placed per frame as instances in a second, small scene (docs/style.md).
// A query asks the static scene and then, up to the static hit, the instance scene. Rays can see
// everything or the static objects only: the static pass and negative photons need the latter.
#pragma once

#include <embree3/rtcore.h>

#include <memory>
#include <optional>
#include <vector>

#include "steadylight/base/bounding_sphere.h"
#include "steadylight/base/ray.h"
#include "steadylight/scene/scene.h"

namespace steadylight {

/// What a ray can meet: every object, or the static ones only (the localized method's static
/// scene); the `_opaque` kinds look through glass (dielectric objects), as the probes of where
/// photons land do (photons/surface_coverage.cpp).
enum class Visibility { everything, static_only, opaque, static_opaque };

/// The same objects, glass left out.
constexpr Visibility opaque_only(Visibility visibility) {
    return visibility == Visibility::everything || visibility == Visibility::opaque ? Visibility::opaque
                                                                                    : Visibility::static_opaque;
}

/// The nearest surface a ray meets: which object and primitive, and where along the ray.
struct Hit {
    float t = 0;
    int object = -1;
    int primitive = -1;
    float u = 0, v = 0;  // barycentrics of vertices 1 and 2 (triangles)
};

/// What the alpha test of one cut-out mesh reads (ray_tracer.cpp).
struct AlphaTest;

class RayTracer {
public:
    /// Builds the static scene and the dynamic objects' own scenes, and places the dynamic
    /// objects as at `frame`.
    RayTracer(const Scene& scene, const FrameState& frame);
    ~RayTracer();
    RayTracer(const RayTracer&) = delete;
    RayTracer& operator=(const RayTracer&) = delete;

    /// Moves the dynamic objects to their placement at `frame` (cheap: instance transforms only).
    void set_frame(const FrameState& frame);

    std::optional<Hit> intersect(const Ray& ray, Visibility visibility = Visibility::everything) const;
    bool occluded(const Ray& ray, Visibility visibility = Visibility::everything) const;
    /// Whether intersect(ray) meets a dynamic object, for a ray whose nearest hit among the static
    /// objects (intersect(ray, Visibility::static_only)) is at `static_t` (infinity: none).
    /// Exactly intersect()'s own decision, without its query of the static scene: the instance
    /// query it makes next, cut at the same distance.
    bool meets_dynamic(const Ray& ray, float static_t) const;
    /// Whether occluded(ray) holds, for a ray that occluded(ray, Visibility::static_only) does not
    /// stop: exactly occluded()'s own decision, without its query of the static scene.
    bool occluded_by_dynamic(const Ray& ray) const { return occluded_by_instances(ray, Visibility::everything); }
    /// A sphere about each dynamic object as placed at this frame (about its box, padded).
    const std::vector<BoundingSphere>& dynamic_bounds() const { return m_dynamic_bounds; }

    /// The Embree scenes, for the benchmark that compares this interface with raw Embree calls.
    RTCScene static_embree_scene() const { return m_static_scene; }
    RTCScene instance_embree_scene() const { return m_instance_scene; }

private:
    void add_static_object(int object, const Transform& world_from_object);
    void add_instanced_object(int object, unsigned mask);
    /// False when the ray cannot meet any instance before `tmax`, so Embree need not be asked.
    bool may_hit_instances(const Ray& ray, float tmax, Visibility visibility) const;
    /// Whether an instance seen with `visibility` stops the ray (occluded()'s second query).
    bool occluded_by_instances(const Ray& ray, Visibility visibility) const;

    /// Makes hits on the object's cut-out parts pass through (glTF alpha MASK), for every ray.
    void attach_alpha_test(RTCGeometry geometry, int object);

    const Scene& m_scene;
    std::vector<std::unique_ptr<AlphaTest>> m_alpha_tests;
    RTCScene m_static_scene = nullptr;
    RTCScene m_instance_scene = nullptr;  // dynamic objects, and static ones that cannot be baked
    std::vector<RTCScene> m_object_scenes;
    std::vector<int> m_static_geometry_object;  // static scene geomID -> object
    std::vector<int> m_instance_object;         // instance scene geomID -> object
    bool m_has_static_instances = false;
    Vec3 m_instance_bounds_lo, m_instance_bounds_hi;  // of the instance scene at this frame; empty if none
    std::vector<BoundingSphere> m_object_bounds;      // per object, in its own space (instanced objects only)
    std::vector<BoundingSphere> m_dynamic_bounds;     // the dynamic objects' at this frame
    /// Beside each of m_dynamic_bounds: for a sphere primitive (its bounds share its centre), the
    /// squared distance from the centre beyond which a ray's start is outside it; infinity else.
    std::vector<float> m_dynamic_outside2;
    bool m_spheres_bound_instances = false;  // every instance is dynamic: m_dynamic_bounds bound them
};

/// One flat Embree scene holding every object placed as at `frame`, for the benchmark that
/// compares RayTracer with the plainest use of raw Embree. The caller releases it.
RTCScene build_flat_embree_scene(const Scene& scene, const FrameState& frame);

}  // namespace steadylight
