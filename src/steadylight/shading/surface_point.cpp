#include "steadylight/shading/surface_point.h"

namespace steadylight {
namespace {

void set_triangle_normals(SurfacePoint& sp, const TriangleMesh& mesh, const Transform& world_from_object,
                          const Hit& hit) {
    const size_t i = size_t(hit.primitive) * 3;
    const int i0 = mesh.indices[i], i1 = mesh.indices[i + 1], i2 = mesh.indices[i + 2];
    const Vec3 p0 = mesh.positions[size_t(i0)];
    const Vec3 ng_object = cross(mesh.positions[size_t(i1)] - p0, mesh.positions[size_t(i2)] - p0);
    sp.ng = normalize(world_from_object.normal(ng_object));
    sp.ns = sp.ng;
    if (mesh.normals.empty()) return;
    const float w0 = 1 - hit.u - hit.v;
    const Vec3 n_object = mesh.normals[size_t(i0)] * w0 + mesh.normals[size_t(i1)] * hit.u +
                          mesh.normals[size_t(i2)] * hit.v;
    const Vec3 ns = world_from_object.normal(n_object);
    if (length2(ns) == 0 || !is_finite(ns)) return;
    sp.ns = normalize(ns);
    // Vertex normals say which side is the front, whatever the winding order.
    if (dot(sp.ns, sp.ng) < 0) sp.ng = -sp.ng;
}

}  // namespace

SurfacePoint make_surface_point(const Scene& scene, const FrameState& frame, const Ray& ray, const Hit& hit) {
    SurfacePoint sp;
    sp.object = hit.object;
    sp.p = ray.o + ray.d * hit.t;
    const Transform& world_from_object = frame.world_from_object[size_t(hit.object)];
    const Geometry& geometry = scene.object(hit.object).geometry;
    if (const auto* mesh = std::get_if<TriangleMesh>(&geometry)) {
        set_triangle_normals(sp, *mesh, world_from_object, hit);
    } else {
        const Vec3 p_object = world_from_object.inverse().point(sp.p);
        sp.ng = normalize(world_from_object.normal(p_object - std::get<Sphere>(geometry).center));
        sp.ns = sp.ng;
    }
    return sp;
}

Rgb emitted_radiance(const ObjectDesc& object, Rgb Le, Vec3 ng, Vec3 w) {
    return object.two_sided_emission || dot(ng, w) > 0 ? Le : Rgb{};
}

std::optional<Bounce> sample_bounce(const Bsdf& bsdf, const SurfacePoint& sp, Vec3 d, Vec2 u, float u_lobe,
                                    TransportMode mode) {
    const Frame frame = Frame::from_normal(sp.ns);
    const std::optional<BsdfSample> bs = bsdf.sample(frame.to_local(-d), u, u_lobe, mode);
    if (!bs) return std::nullopt;
    return Bounce{*bs, spawn_ray(sp.p, sp.ng, frame.to_world(bs->wi))};
}

}  // namespace steadylight
