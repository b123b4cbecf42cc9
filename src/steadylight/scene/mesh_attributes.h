// A mesh's per-vertex surface attributes at a point of a triangle (texture coordinates, vertex
// colours) and what a material's textures make of them there: the base colour with its alpha,
// metallic and roughness, the emission's tint. Shared by the ray tracer's alpha test (trace/)
// and the BSDFs made per hit (shading/).
#pragma once

#include "steadylight/scene/scene_desc.h"

namespace steadylight {

/// Where a ray met a triangle: its index and the barycentrics of its vertices 1 and 2.
struct TrianglePoint {
    int primitive = 0;
    float u = 0, v = 0;
};

/// Texture coordinate set `set` (0 or 1) at the point; (0, 0) when the mesh has none.
Vec2 interpolate_uv(const TriangleMesh& mesh, int set, TrianglePoint at);
/// COLOR_0 at the point; white when the mesh has none.
Rgba interpolate_color(const TriangleMesh& mesh, TrianglePoint at);
/// TANGENT at the point (object space, w the bitangent's sign); (1, 0, 0, 1) when the mesh has none.
Rgba interpolate_tangent(const TriangleMesh& mesh, TrianglePoint at);

/// Both texture coordinate sets and the vertex colour at a point.
struct SurfaceAttributes {
    Vec2 uv[2];
    Rgba color{1, 1, 1, 1};
};
SurfaceAttributes surface_attributes(const TriangleMesh& mesh, TrianglePoint at);

/// The material's base colour and alpha there: factor x texture (sRGB decoded) x vertex colour.
Rgba base_color_at(const SceneDesc& desc, const MaterialDesc& m, const SurfaceAttributes& a);
/// Metallic and roughness there: the factors times the texture's blue and green channels.
Vec2 metallic_roughness_at(const SceneDesc& desc, const MaterialDesc& m, const SurfaceAttributes& a);
/// The emissive texture's (sRGB decoded) colour there; white without one.
Rgb emissive_tint_at(const SceneDesc& desc, const MaterialDesc& m, const SurfaceAttributes& a);
/// True when the material cuts the point out (alpha mode MASK or BLEND, alpha below the cutoff).
bool is_cut_out(const SceneDesc& desc, const MaterialDesc& m, const TriangleMesh& mesh, TrianglePoint at);

}  // namespace steadylight
