#include "steadylight/trace/ray_tracer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "steadylight/scene/mesh_attributes.h"
#include "steadylight/trace/embree_device.h"

namespace steadylight {

struct AlphaTest {
    const SceneDesc& desc;
    const MaterialDesc& material;
    const TriangleMesh& mesh;
};

namespace {

/// Embree's intersection and occlusion filter: rejects hits where the material is cut out.
void alpha_filter(const RTCFilterFunctionNArguments* args) {
    const auto* test = static_cast<const AlphaTest*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const TrianglePoint at{int(RTCHitN_primID(args->hit, args->N, i)), RTCHitN_u(args->hit, args->N, i),
                               RTCHitN_v(args->hit, args->N, i)};
        if (is_cut_out(test->desc, test->material, test->mesh, at)) args->valid[i] = 0;
    }
}

// Geometry masks: static or dynamic, opaque or glass.
constexpr unsigned static_mask = 1u;
constexpr unsigned dynamic_mask = 2u;
constexpr unsigned static_glass_mask = 4u;
constexpr unsigned dynamic_glass_mask = 8u;

unsigned ray_mask(Visibility visibility) {
    switch (visibility) {
        case Visibility::everything:
            return ~0u;
        case Visibility::static_only:
            return static_mask | static_glass_mask;
        case Visibility::opaque:
            return static_mask | dynamic_mask;
        case Visibility::static_opaque:
            return static_mask;
    }
    return ~0u;
}

bool sees_dynamic(Visibility visibility) {
    return visibility == Visibility::everything || visibility == Visibility::opaque;
}

bool is_glass(const Scene& scene, int object) {
    return scene.desc().materials[size_t(scene.object(object).material)].type == MaterialType::dielectric;
}

RTCGeometry make_triangle_geometry(const TriangleMesh& mesh, const Transform& to_space) {
    RTCGeometry geometry = rtcNewGeometry(embree_device(), RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), mesh.positions.size()));
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const Vec3 p = to_space.point(mesh.positions[i]);
        vertices[3 * i] = p.x;
        vertices[3 * i + 1] = p.y;
        vertices[3 * i + 2] = p.z;
    }
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), mesh.indices.size() / 3));
    for (size_t i = 0; i < mesh.indices.size(); ++i) indices[i] = unsigned(mesh.indices[i]);
    return geometry;
}

RTCGeometry make_sphere_geometry(Vec3 center, float radius) {
    RTCGeometry geometry = rtcNewGeometry(embree_device(), RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
    v[0] = center.x;
    v[1] = center.y;
    v[2] = center.z;
    v[3] = radius;
    return geometry;
}

/// The uniform scale of a similarity transform, or nothing when it scales unevenly or shears.
std::optional<float> uniform_scale(const Transform& t) {
    const Vec3 x = t.vector({1, 0, 0}), y = t.vector({0, 1, 0}), z = t.vector({0, 0, 1});
    const float s = length(x);
    const float tolerance = 1e-5f * s;
    if (std::abs(length(y) - s) > tolerance || std::abs(length(z) - s) > tolerance) return std::nullopt;
    if (std::abs(dot(x, y)) > tolerance * s || std::abs(dot(y, z)) > tolerance * s ||
        std::abs(dot(x, z)) > tolerance * s)
        return std::nullopt;
    return s;
}

/// The geometry placed in world space, or nullptr for a sphere that is not scaled uniformly.
RTCGeometry make_world_geometry(const Geometry& geometry, const Transform& world_from_object) {
    if (const auto* mesh = std::get_if<TriangleMesh>(&geometry))
        return make_triangle_geometry(*mesh, world_from_object);
    const Sphere& sphere = std::get<Sphere>(geometry);
    const std::optional<float> scale = uniform_scale(world_from_object);
    if (!scale) return nullptr;
    return make_sphere_geometry(world_from_object.point(sphere.center), sphere.radius * *scale);
}

/// Attaches and releases the geometry (the scene keeps it alive), returning its ID.
unsigned attach(RTCScene scene, RTCGeometry geometry) {
    rtcCommitGeometry(geometry);
    const unsigned id = rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);
    return id;
}

RTCRay make_embree_ray(const Ray& ray, Visibility visibility) {
    RTCRay r;
    r.org_x = ray.o.x;
    r.org_y = ray.o.y;
    r.org_z = ray.o.z;
    r.tnear = 0;
    r.dir_x = ray.d.x;
    r.dir_y = ray.d.y;
    r.dir_z = ray.d.z;
    r.time = 0;
    r.tfar = ray.tmax;
    r.mask = ray_mask(visibility);
    r.id = 0;
    r.flags = 0;
    return r;
}

/// A sphere about `geometry` in its own space: the sphere itself, or a mesh's vertices about
/// their box's centre (tighter than the sphere about the box: a ball's is 1.7 times its radius).
BoundingSphere object_bounds(const Geometry& geometry) {
    if (const auto* sphere = std::get_if<Sphere>(&geometry)) return {sphere->center, sphere->radius};
    const TriangleMesh& mesh = std::get<TriangleMesh>(geometry);
    Vec3 lo{infinity, infinity, infinity}, hi = -lo;
    for (const Vec3 p : mesh.positions) lo = min(lo, p), hi = max(hi, p);
    BoundingSphere bounds = BoundingSphere::of_box(lo, hi);
    if (bounds.empty()) return bounds;
    bounds.radius = 0;
    for (const Vec3 p : mesh.positions) bounds.radius = std::max(bounds.radius, length(p - bounds.center));
    return bounds;
}

/// The most `t` stretches a length: its largest singular value, bounded above (Gershgorin) by
/// the largest row sum of |M^T M| for its linear part M. Exact, but for rounding, where M's
/// columns are orthogonal (every translation-rotation-scale); larger where a placement chain
/// shears, where the longest column would fall short.
float largest_stretch(const Transform& t) {
    const Vec3 axes[3] = {t.vector({1, 0, 0}), t.vector({0, 1, 0}), t.vector({0, 0, 1})};
    float largest2 = 0;
    for (const Vec3 a : axes)
        largest2 =
            std::max(largest2, std::abs(dot(a, axes[0])) + std::abs(dot(a, axes[1])) + std::abs(dot(a, axes[2])));
    return std::sqrt(largest2);
}

/// `bounds` placed by `t` (its radius scaled by t's largest stretch), padded for rounding.
BoundingSphere placed_bounds(const BoundingSphere& bounds, const Transform& t) {
    if (bounds.empty()) return bounds;
    const Vec3 center = t.point(bounds.center);
    const float radius = bounds.radius * largest_stretch(t);
    return {center, radius * 1.0001f + ray_epsilon(max(-center, center) + Vec3{1, 1, 1} * radius)};
}

/// For a sphere primitive placed by `t` (an ellipsoid where `t` scales unevenly, inside the sphere
/// of its largest stretch): the squared distance from its placed centre beyond which a point is
/// outside it, by a margin of a hundred-thousandth of its radius and of its centre's
/// distance from the origin, a hundred times the rounding of the placement and of Embree's map of
/// a ray into the sphere's space. A ray offset off its surface (ray_epsilon) starts ten times
/// farther out. Infinity for a mesh, where no start is known to be outside.
float outside_sphere2(const Geometry& geometry, const Transform& t) {
    const auto* sphere = std::get_if<Sphere>(&geometry);
    if (!sphere) return infinity;
    const Vec3 center = t.point(sphere->center);
    const float radius = sphere->radius * largest_stretch(t);
    const float outside =
        radius * (1 + 1e-5f) + 1e-5f * (1 + std::max({std::abs(center.x), std::abs(center.y), std::abs(center.z)}));
    return outside * outside;
}

}  // namespace

RayTracer::RayTracer(const Scene& scene, const FrameState& frame) : m_scene(scene) {
    m_static_scene = rtcNewScene(embree_device());
    rtcSetSceneBuildQuality(m_static_scene, RTC_BUILD_QUALITY_HIGH);
    m_instance_scene = rtcNewScene(embree_device());
    rtcSetSceneFlags(m_instance_scene, RTC_SCENE_FLAG_DYNAMIC);
    rtcSetSceneBuildQuality(m_instance_scene, RTC_BUILD_QUALITY_LOW);
    m_object_scenes.assign(scene.objects().size(), nullptr);

    for (const int object : scene.static_objects()) add_static_object(object, frame.world_from_object[size_t(object)]);
    for (const int object : scene.dynamic_objects())
        add_instanced_object(object, is_glass(scene, object) ? dynamic_glass_mask : dynamic_mask);
    rtcCommitScene(m_static_scene);
    set_frame(frame);
}

RayTracer::~RayTracer() {
    rtcReleaseScene(m_static_scene);
    rtcReleaseScene(m_instance_scene);
    for (RTCScene s : m_object_scenes)
        if (s) rtcReleaseScene(s);
}

RTCScene build_flat_embree_scene(const Scene& scene, const FrameState& frame) {
    RTCScene flat = rtcNewScene(embree_device());
    rtcSetSceneBuildQuality(flat, RTC_BUILD_QUALITY_HIGH);
    for (int object = 0; object < int(scene.objects().size()); ++object) {
        const RTCGeometry g =
            make_world_geometry(scene.object(object).geometry, frame.world_from_object[size_t(object)]);
        if (!g) throw std::runtime_error("build_flat_embree_scene: unevenly scaled sphere");
        attach(flat, g);
    }
    rtcCommitScene(flat);
    return flat;
}

void RayTracer::attach_alpha_test(RTCGeometry geometry, int object) {
    const ObjectDesc& o = m_scene.object(object);
    const MaterialDesc& material = m_scene.desc().materials[size_t(o.material)];
    const auto* mesh = std::get_if<TriangleMesh>(&o.geometry);
    if (!mesh || !material.has_cutouts()) return;
    m_alpha_tests.push_back(std::make_unique<AlphaTest>(AlphaTest{m_scene.desc(), material, *mesh}));
    rtcSetGeometryUserData(geometry, m_alpha_tests.back().get());
    rtcSetGeometryIntersectFilterFunction(geometry, alpha_filter);
    rtcSetGeometryOccludedFilterFunction(geometry, alpha_filter);
}

void RayTracer::add_static_object(int object, const Transform& world_from_object) {
    const RTCGeometry g = make_world_geometry(m_scene.object(object).geometry, world_from_object);
    // Embree spheres cannot be stretched: an unevenly scaled sphere goes in as an instance.
    const bool glass = is_glass(m_scene, object);
    if (!g) return add_instanced_object(object, glass ? static_glass_mask : static_mask);
    attach_alpha_test(g, object);
    rtcSetGeometryMask(g, glass ? static_glass_mask : static_mask);
    const unsigned id = attach(m_static_scene, g);
    m_static_geometry_object.resize(id + 1, -1);
    m_static_geometry_object[id] = object;
}

void RayTracer::add_instanced_object(int object, unsigned mask) {
    // Build the object once, in its own space; each frame only moves its instance.
    RTCScene object_scene = rtcNewScene(embree_device());
    rtcSetSceneBuildQuality(object_scene, RTC_BUILD_QUALITY_HIGH);
    const Geometry& geometry = m_scene.object(object).geometry;
    m_object_bounds.resize(m_scene.objects().size());
    m_object_bounds[size_t(object)] = object_bounds(geometry);
    if (const auto* mesh = std::get_if<TriangleMesh>(&geometry)) {
        const RTCGeometry g = make_triangle_geometry(*mesh, Transform{});
        attach_alpha_test(g, object);
        attach(object_scene, g);
    } else {
        attach(object_scene,
               make_sphere_geometry(std::get<Sphere>(geometry).center, std::get<Sphere>(geometry).radius));
    }
    rtcCommitScene(object_scene);
    m_object_scenes[size_t(object)] = object_scene;

    RTCGeometry instance = rtcNewGeometry(embree_device(), RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(instance, object_scene);
    rtcSetGeometryMask(instance, mask);
    const unsigned id = rtcAttachGeometry(m_instance_scene, instance);
    rtcReleaseGeometry(instance);
    m_instance_object.resize(id + 1, -1);
    m_instance_object[id] = object;
    m_has_static_instances |= (mask & (static_mask | static_glass_mask)) != 0;
}

void RayTracer::set_frame(const FrameState& frame) {
    m_dynamic_bounds.clear();
    m_dynamic_outside2.clear();
    for (size_t id = 0; id < m_instance_object.size(); ++id) {
        const int object = m_instance_object[id];
        const Transform& t = frame.world_from_object[size_t(object)];
        RTCGeometry instance = rtcGetGeometry(m_instance_scene, unsigned(id));
        rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, &t.m[0][0]);
        rtcCommitGeometry(instance);
        if (m_scene.object(object).is_dynamic()) {
            m_dynamic_bounds.push_back(placed_bounds(m_object_bounds[size_t(object)], t));
            m_dynamic_outside2.push_back(outside_sphere2(m_scene.object(object).geometry, t));
        }
    }
    rtcCommitScene(m_instance_scene);
    RTCBounds bounds;
    rtcGetSceneBounds(m_instance_scene, &bounds);
    // Pad the box a little so that float rounding in the slab test never loses a grazing hit.
    const Vec3 lo{bounds.lower_x, bounds.lower_y, bounds.lower_z}, hi{bounds.upper_x, bounds.upper_y, bounds.upper_z};
    const Vec3 pad = (hi - lo) * 1e-4f + Vec3{1, 1, 1} * ray_epsilon(max(-lo, hi));
    m_instance_bounds_lo = lo - pad;
    m_instance_bounds_hi = hi + pad;
    if (m_instance_object.empty()) m_instance_bounds_lo = {1, 1, 1}, m_instance_bounds_hi = {-1, -1, -1};
    m_spheres_bound_instances = m_dynamic_bounds.size() == m_instance_object.size() &&
                                std::none_of(m_dynamic_bounds.begin(), m_dynamic_bounds.end(),
                                             [](const BoundingSphere& s) { return s.empty(); });
}

bool RayTracer::may_hit_instances(const Ray& ray, float tmax, Visibility visibility) const {
    if (!sees_dynamic(visibility) && !m_has_static_instances) return false;
    // Slab test against the instances' bounding box: most rays pass far from the few moving
    // objects, and this is cheaper than a second Embree query that finds nothing.
    float t0 = 0, t1 = tmax;
    for (int axis = 0; axis < 3; ++axis) {
        const float inv_d = 1 / ray.d[axis];
        float t_near = (m_instance_bounds_lo[axis] - ray.o[axis]) * inv_d;
        float t_far = (m_instance_bounds_hi[axis] - ray.o[axis]) * inv_d;
        if (t_near > t_far) std::swap(t_near, t_far);
        t0 = t_near > t0 ? t_near : t0;
        t1 = t_far < t1 ? t_far : t1;
        if (!(t0 <= t1)) return false;
    }
    // Then, where the instances are the dynamic objects alone, each object: the sphere about it
    // (about a third of the rays through the box of a ball pass beside the ball), and, for a
    // sphere primitive, whose bounds share its centre, whether the ray starts outside it and heads
    // away from its centre (its own points' shadow rays and gathers): the distance from the
    // centre only grows along such a ray.
    if (!m_spheres_bound_instances) return true;
    for (size_t i = 0; i < m_dynamic_bounds.size(); ++i) {
        if (!may_meet_ray(m_dynamic_bounds[i], ray.o, ray.d, tmax)) continue;
        const Vec3 from_center = ray.o - m_dynamic_bounds[i].center;
        if (length2(from_center) >= m_dynamic_outside2[i] && dot(ray.d, from_center) >= 0) continue;
        return true;
    }
    return false;
}

std::optional<Hit> RayTracer::intersect(const Ray& ray, Visibility visibility) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rayhit;
    rayhit.ray = make_embree_ray(ray, visibility);
    rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_static_scene, &context, &rayhit);
    // The instance query starts with tfar cut down to the static hit, so it only looks closer.
    if (may_hit_instances(ray, rayhit.ray.tfar, visibility)) rtcIntersect1(m_instance_scene, &context, &rayhit);
    if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

    Hit hit;
    hit.t = rayhit.ray.tfar;
    hit.primitive = int(rayhit.hit.primID);
    hit.u = rayhit.hit.u;
    hit.v = rayhit.hit.v;
    hit.object = rayhit.hit.instID[0] != RTC_INVALID_GEOMETRY_ID ? m_instance_object[rayhit.hit.instID[0]]
                                                                 : m_static_geometry_object[rayhit.hit.geomID];
    return hit;
}

bool RayTracer::meets_dynamic(const Ray& ray, float static_t) const {
    // Static objects placed as instances share the instance scene: then only the whole query
    // says which is nearer.
    if (m_has_static_instances) {
        const std::optional<Hit> hit = intersect(ray);
        return hit && m_scene.object(hit->object).is_dynamic();
    }
    if (!may_hit_instances(ray, static_t, Visibility::everything)) return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rayhit;
    rayhit.ray = make_embree_ray(ray, Visibility::everything);
    rayhit.ray.tfar = static_t;
    rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_instance_scene, &context, &rayhit);
    return rayhit.hit.instID[0] != RTC_INVALID_GEOMETRY_ID;
}

bool RayTracer::occluded(const Ray& ray, Visibility visibility) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r = make_embree_ray(ray, visibility);
    rtcOccluded1(m_static_scene, &context, &r);
    // A ray nothing stops leaves the query as it came: the instances are asked the same ray.
    return r.tfar == -infinity || occluded_by_instances(ray, visibility);
}

bool RayTracer::occluded_by_instances(const Ray& ray, Visibility visibility) const {
    if (!may_hit_instances(ray, ray.tmax, visibility)) return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r = make_embree_ray(ray, visibility);
    rtcOccluded1(m_instance_scene, &context, &r);
    return r.tfar == -infinity;
}

}  // namespace steadylight
