// Surface attributes and material textures at a point (mesh_attributes.h).
#include "steadylight/scene/mesh_attributes.h"

#include <type_traits>

namespace steadylight {
namespace {

template <class T>
T interpolate(const std::vector<T>& values, const std::vector<int>& indices, TrianglePoint at, T fallback) {
    const size_t i = size_t(at.primitive) * 3;
    if (values.empty() || i + 2 >= indices.size()) return fallback;
    const float w0 = 1 - at.u - at.v;
    const T& a = values[size_t(indices[i])];
    const T& b = values[size_t(indices[i + 1])];
    const T& c = values[size_t(indices[i + 2])];
    if constexpr (std::is_same_v<T, Vec2>) {
        return {a.x * w0 + b.x * at.u + c.x * at.v, a.y * w0 + b.y * at.u + c.y * at.v};
    } else {
        T out;
        for (size_t k = 0; k < out.size(); ++k) out[k] = a[k] * w0 + b[k] * at.u + c[k] * at.v;
        return out;
    }
}

Rgba sample(const SceneDesc& desc, const TextureRef& ref, const SurfaceAttributes& a, bool srgb) {
    return sample_texture(desc.images[size_t(ref.image)], ref, a.uv[ref.texcoord], srgb);
}

}  // namespace

Vec2 interpolate_uv(const TriangleMesh& mesh, int set, TrianglePoint at) {
    return interpolate(set == 1 ? mesh.uv1 : mesh.uv0, mesh.indices, at, Vec2{});
}

Rgba interpolate_color(const TriangleMesh& mesh, TrianglePoint at) {
    return interpolate(mesh.colors, mesh.indices, at, Rgba{1, 1, 1, 1});
}

Rgba interpolate_tangent(const TriangleMesh& mesh, TrianglePoint at) {
    return interpolate(mesh.tangents, mesh.indices, at, Rgba{1, 0, 0, 1});
}

SurfaceAttributes surface_attributes(const TriangleMesh& mesh, TrianglePoint at) {
    return {{interpolate_uv(mesh, 0, at), interpolate_uv(mesh, 1, at)}, interpolate_color(mesh, at)};
}

Rgba base_color_at(const SceneDesc& desc, const MaterialDesc& m, const SurfaceAttributes& a) {
    Rgba c{m.reflectance.r * a.color[0], m.reflectance.g * a.color[1], m.reflectance.b * a.color[2],
           m.alpha * a.color[3]};
    if (m.base_color_texture.is_set()) {
        const Rgba t = sample(desc, m.base_color_texture, a, true);
        for (size_t k = 0; k < 4; ++k) c[k] *= t[k];
    }
    return c;
}

Vec2 metallic_roughness_at(const SceneDesc& desc, const MaterialDesc& m, const SurfaceAttributes& a) {
    if (!m.metallic_roughness_texture.is_set()) return {m.metallic, m.roughness};
    const Rgba t = sample(desc, m.metallic_roughness_texture, a, false);
    return {m.metallic * t[2], m.roughness * t[1]};
}

Rgb emissive_tint_at(const SceneDesc& desc, const MaterialDesc& m, const SurfaceAttributes& a) {
    if (!m.emissive_texture.is_set()) return {1, 1, 1};
    const Rgba t = sample(desc, m.emissive_texture, a, true);
    return {t[0], t[1], t[2]};
}

bool is_cut_out(const SceneDesc& desc, const MaterialDesc& m, const TriangleMesh& mesh, TrianglePoint at) {
    if (!m.has_cutouts()) return false;
    return base_color_at(desc, m, surface_attributes(mesh, at))[3] < m.alpha_cutoff;
}

}  // namespace steadylight
