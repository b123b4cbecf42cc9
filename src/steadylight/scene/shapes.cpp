#include "steadylight/scene/shapes.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <string_view>

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include "steadylight/base/error.h"
#include "steadylight/base/input_file.h"

namespace steadylight {

TriangleMesh make_quad(Vec3 corner, Vec3 edge_u, Vec3 edge_v) {
    TriangleMesh mesh;
    mesh.positions = {corner, corner + edge_u, corner + edge_u + edge_v, corner + edge_v};
    mesh.indices = {0, 1, 2, 0, 2, 3};
    return mesh;
}

void generate_tangents(TriangleMesh& mesh, int texcoord) {
    const std::vector<Vec2>& uv = texcoord == 1 ? mesh.uv1 : mesh.uv0;
    const size_t n = mesh.positions.size();
    mesh.tangents.assign(n, Rgba{1, 0, 0, 1});
    if (uv.size() != n) return;
    // Accumulate each triangle's dp/du and dp/dv at its corners (Lengyel 2001).
    std::vector<Vec3> sum_t(n), sum_b(n);
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const size_t a = size_t(mesh.indices[i]), b = size_t(mesh.indices[i + 1]), c = size_t(mesh.indices[i + 2]);
        const Vec3 e1 = mesh.positions[b] - mesh.positions[a], e2 = mesh.positions[c] - mesh.positions[a];
        const float du1 = uv[b].x - uv[a].x, dv1 = uv[b].y - uv[a].y, du2 = uv[c].x - uv[a].x, dv2 = uv[c].y - uv[a].y;
        const float det = du1 * dv2 - du2 * dv1;
        if (!(std::abs(det) > 1e-20f)) continue;
        const Vec3 t = (e1 * dv2 - e2 * dv1) / det, bt = (e2 * du1 - e1 * du2) / det;
        for (const size_t v : {a, b, c}) sum_t[v] += t, sum_b[v] += bt;
    }
    // Orthogonalise against the vertex normal (or the accumulated frame's own normal).
    for (size_t v = 0; v < n; ++v) {
        const Vec3 nrm = mesh.normals.empty() ? normalize(cross(sum_t[v], sum_b[v])) : mesh.normals[v];
        Vec3 t = sum_t[v] - nrm * dot(nrm, sum_t[v]);
        if (!(length2(t) > 0) || !is_finite(t) || !is_finite(nrm)) continue;
        t = normalize(t);
        const float w = dot(cross(nrm, t), sum_b[v]) < 0 ? -1.0f : 1.0f;
        mesh.tangents[v] = {t.x, t.y, t.z, w};
    }
}

TriangleMesh make_box(Vec3 center, Vec3 size) {
    TriangleMesh mesh;
    const Vec3 h = size * 0.5f;
    // Each face: a corner and two edges; cross(second, first) points outward.
    const Vec3 faces[6][3] = {
        {{-h.x, -h.y, -h.z}, {0, 0, size.z}, {size.x, 0, 0}},  // bottom, -y
        {{-h.x, h.y, -h.z}, {size.x, 0, 0}, {0, 0, size.z}},   // top, +y
        {{-h.x, -h.y, -h.z}, {0, size.y, 0}, {0, 0, size.z}},  // -x
        {{h.x, -h.y, -h.z}, {0, 0, size.z}, {0, size.y, 0}},   // +x
        {{-h.x, -h.y, -h.z}, {size.x, 0, 0}, {0, size.y, 0}},  // -z
        {{-h.x, -h.y, h.z}, {0, size.y, 0}, {size.x, 0, 0}},   // +z
    };
    for (const auto& face : faces) {
        const TriangleMesh quad = make_quad(center + face[0], face[2], face[1]);
        const int base = int(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), quad.positions.begin(), quad.positions.end());
        for (const int i : quad.indices) mesh.indices.push_back(base + i);
    }
    return mesh;
}

namespace {

/// The OBJ file with only the statements a mesh is made of (v, vt, vn, f, o, g, s): the others
/// (materials, vertex weights, lines, points, curves) become empty lines, so that tinyobjloader
/// neither reads material files nor meets what it mishandles (a `vw` weight of 1e999 converted
/// to int, found by fuzzing), and its messages keep their line numbers. Lines end as
/// tinyobjloader ends them: at "\n", "\r\n" or a lone "\r" (a `vw` after a lone "\r" reached
/// it, found by fuzzing too).
std::string mesh_statements_of_obj(const std::string& path, const InputFolder& inputs) {
    const std::string file = read_input_file(path, inputs);
    std::string text;
    for (size_t begin = 0; begin < file.size();) {
        const size_t end = std::min(file.find_first_of("\r\n", begin), file.size());
        const std::string_view line = std::string_view(file).substr(begin, end - begin);
        const size_t start = line.find_first_not_of(" \t");
        const std::string_view rest = start == std::string::npos ? std::string_view() : line.substr(start);
        const std::string_view keyword = rest.substr(0, rest.find_first_of(" \t"));
        if (keyword == "v" || keyword == "vt" || keyword == "vn" || keyword == "f" || keyword == "o" ||
            keyword == "g" || keyword == "s")
            text += line;
        text += '\n';
        begin = end + (file.compare(end, 2, "\r\n") == 0 ? 2 : 1);
    }
    return text;
}

/// A coordinate of the file (parsed as double) as a float; an error beyond float's range.
float obj_coordinate(double value, const std::string& path) {
    if (!(std::abs(value) <= double(std::numeric_limits<float>::max())))
        throw InputError(path, fmt::format("coordinate {} is not a finite float", value));
    return float(value);
}

}  // namespace

TriangleMesh load_obj_mesh(const std::string& path, const InputFolder& inputs) {
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromString(mesh_statements_of_obj(path, inputs), "", config))
        throw InputError(path, reader.Error().empty() ? "cannot read OBJ file" : reader.Error());

    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    TriangleMesh mesh;
    bool all_normals = true;
    std::vector<Vec3> normals;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        for (const tinyobj::index_t& index : shape.mesh.indices) {
            const size_t v = size_t(index.vertex_index);
            if (index.vertex_index < 0 || 3 * v + 2 >= attrib.vertices.size())
                throw InputError(path, "face refers to a missing vertex");
            mesh.indices.push_back(int(mesh.positions.size()));
            mesh.positions.push_back({obj_coordinate(attrib.vertices[3 * v], path),
                                      obj_coordinate(attrib.vertices[3 * v + 1], path),
                                      obj_coordinate(attrib.vertices[3 * v + 2], path)});
            const size_t n = size_t(index.normal_index);
            if (index.normal_index < 0 || 3 * n + 2 >= attrib.normals.size()) {
                all_normals = false;
                continue;
            }
            normals.push_back({obj_coordinate(attrib.normals[3 * n], path),
                               obj_coordinate(attrib.normals[3 * n + 1], path),
                               obj_coordinate(attrib.normals[3 * n + 2], path)});
        }
    }
    if (mesh.indices.empty()) throw InputError(path, "OBJ file has no faces");
    if (all_normals) mesh.normals = std::move(normals);
    return mesh;
}

float mesh_area(const TriangleMesh& mesh) {
    float area = 0;
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const Vec3 a = mesh.positions[mesh.indices[i]], b = mesh.positions[mesh.indices[i + 1]],
                   c = mesh.positions[mesh.indices[i + 2]];
        area += 0.5f * length(cross(b - a, c - a));
    }
    return area;
}

}  // namespace steadylight
