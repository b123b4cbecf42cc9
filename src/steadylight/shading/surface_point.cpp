#include "steadylight/shading/surface_point.h"

#include <cmath>

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
    const Vec3 n_object =
        mesh.normals[size_t(i0)] * w0 + mesh.normals[size_t(i1)] * hit.u + mesh.normals[size_t(i2)] * hit.v;
    const Vec3 ns = world_from_object.normal(n_object);
    if (length2(ns) == 0 || !is_finite(ns)) return;
    sp.ns = normalize(ns);
    // Vertex normals say which side is the front, whatever the winding order.
    if (dot(sp.ns, sp.ng) < 0) sp.ng = -sp.ng;
}

/// The material's normal map applied to sp.ns (glTF 2.0 §3.9.3): the texel's tangent-space
/// normal in the frame of the interpolated tangent, bitangent and normal.
void apply_normal_map(SurfacePoint& sp, const SceneDesc& desc, const MaterialDesc& m, const TriangleMesh& mesh,
                      const Transform& world_from_object, TrianglePoint at) {
    if (!m.normal_texture.is_set() || mesh.tangents.empty()) return;
    const Rgba tangent = interpolate_tangent(mesh, at);
    const Vec3 t_world = world_from_object.vector({tangent[0], tangent[1], tangent[2]});
    const Vec3 t = t_world - sp.ns * dot(sp.ns, t_world);
    if (!(length2(t) > 0) || !is_finite(t)) return;
    const Vec3 tu = normalize(t);
    const Vec3 b = cross(sp.ns, tu) * (tangent[3] < 0 ? -1.0f : 1.0f);
    const Rgba texel = sample_texture(desc.images[size_t(m.normal_texture.image)], m.normal_texture,
                                      sp.attributes.uv[m.normal_texture.texcoord], false);
    const Vec3 n_tangent{(2 * texel[0] - 1) * m.normal_scale, (2 * texel[1] - 1) * m.normal_scale, 2 * texel[2] - 1};
    const Vec3 n = tu * n_tangent.x + b * n_tangent.y + sp.ns * n_tangent.z;
    // A bent normal that leaves the surface's side is no use: keep the interpolated one.
    if (!(length2(n) > 0) || !is_finite(n) || dot(n, sp.ng) <= 0) return;
    sp.nm = normalize(n);
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
        sp.nm = sp.ns;
        const TrianglePoint at{hit.primitive, hit.u, hit.v};
        sp.attributes = surface_attributes(*mesh, at);
        const MaterialDesc& m = scene.desc().materials[size_t(scene.object(hit.object).material)];
        apply_normal_map(sp, scene.desc(), m, *mesh, world_from_object, at);
    } else {
        const Vec3 p_object = world_from_object.inverse().point(sp.p);
        sp.ng = normalize(world_from_object.normal(p_object - std::get<Sphere>(geometry).center));
        sp.ns = sp.nm = sp.ng;
    }
    return sp;
}

SurfaceBsdf bsdf_at(const FrameContext& context, const SurfacePoint& sp) {
    const ObjectDesc& object = context.scene.object(sp.object);
    const MaterialDesc& m = context.scene.desc().materials[size_t(object.material)];
    const auto* mesh = std::get_if<TriangleMesh>(&object.geometry);
    const bool varies =
        mesh && (m.base_color_texture.is_set() || m.metallic_roughness_texture.is_set() || !mesh->colors.empty());
    if (!varies || (m.type != MaterialType::pbr && m.type != MaterialType::lambert))
        return SurfaceBsdf(context.bsdf_of(sp.object));
    const Rgba base = base_color_at(context.scene.desc(), m, sp.attributes);
    const Rgb base_rgb{base[0], base[1], base[2]};
    if (m.type == MaterialType::lambert) return SurfaceBsdf(make_lambert(base_rgb));
    PbrParams params = pbr_params(m);
    params.base = base_rgb;
    const Vec2 mr = metallic_roughness_at(context.scene.desc(), m, sp.attributes);
    params.metallic = mr.x;
    params.roughness = mr.y;
    return SurfaceBsdf(make_pbr(params));
}

Rgb volume_transmittance(const FrameContext& context, const SurfacePoint& sp, Vec3 d, float distance) {
    if (dot(d, sp.ng) <= 0) return {1, 1, 1};  // arriving from outside
    const Rgb sigma = context.scene.desc().materials[size_t(context.scene.object(sp.object).material)].absorption();
    if (is_black(sigma)) return {1, 1, 1};
    const float length_travelled = distance * length(d);
    return {std::exp(-sigma.r * length_travelled), std::exp(-sigma.g * length_travelled),
            std::exp(-sigma.b * length_travelled)};
}

Rgb emitted_radiance_at(const FrameContext& context, const SurfacePoint& sp, Vec3 w) {
    const ObjectDesc& object = context.scene.object(sp.object);
    const MaterialDesc& m = context.scene.desc().materials[size_t(object.material)];
    const Rgb Le = context.frame.emission[size_t(sp.object)];
    if (is_black(Le)) return {};
    return emitted_radiance(object, Le * emissive_tint_at(context.scene.desc(), m, sp.attributes), sp.ng, w);
}

Rgb emitted_radiance(const ObjectDesc& object, Rgb Le, Vec3 ng, Vec3 w) {
    return object.two_sided_emission || dot(ng, w) > 0 ? Le : Rgb{};
}

std::optional<Bounce> sample_bounce(const Bsdf& bsdf, const SurfacePoint& sp, Vec3 d, Vec2 u, float u_lobe,
                                    TransportMode mode) {
    const OrthonormalBasis basis = OrthonormalBasis::from_normal(sp.nm);
    const std::optional<BsdfSample> bs = bsdf.sample(basis.to_local(-d), u, u_lobe, mode);
    if (!bs) return std::nullopt;
    return Bounce{*bs, spawn_ray(sp.p, sp.ng, basis.to_world(bs->wi))};
}

}  // namespace steadylight
