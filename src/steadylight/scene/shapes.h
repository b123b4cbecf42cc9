// The shapes a scene file can name, turned into geometry in object space: quads and boxes as
// triangle meshes, and triangle meshes read from Wavefront OBJ files.
#pragma once

#include <string>

#include "steadylight/scene/scene_desc.h"

namespace steadylight {

/// The parallelogram corner + a*edge_u + b*edge_v, a, b in [0,1]. Its front normal is
/// normalize(cross(edge_u, edge_v)).
TriangleMesh make_quad(Vec3 corner, Vec3 edge_u, Vec3 edge_v);

/// Per-vertex tangents from texture coordinate set `texcoord` (0 or 1), for normal maps whose
/// mesh has none: each triangle's dp/du averaged at its vertices, orthogonalised against the
/// normal, w = the bitangent's side (Lengyel 2001; glTF asks for MikkTSpace, which agrees on
/// smooth, unmirrored meshes). Vertices without usable coordinates get (1, 0, 0, 1).
void generate_tangents(TriangleMesh& mesh, int texcoord);

/// An axis-aligned box with outward-facing triangles.
TriangleMesh make_box(Vec3 center, Vec3 size);

/// Reads the triangles (and normals, when every vertex has one) of an OBJ file; polygons are
/// triangulated. Materials in the file are ignored: the scene assigns one material per object.
TriangleMesh load_obj_mesh(const std::string& path, const InputFolder& inputs = {});

/// Total area of a mesh in object space (zero for degenerate meshes).
float mesh_area(const TriangleMesh& mesh);

}  // namespace steadylight
