#include "steadylight/shading/mirror_images.h"

#include <cmath>
#include <optional>
#include <variant>

#include "steadylight/base/ray.h"

namespace steadylight {
namespace {

/// The plane of a world-space triangle mesh when every vertex lies in it and every vertex
/// normal is along its normal; none otherwise.
std::optional<MirrorPlane> plane_of(const TriangleMesh& mesh, const Transform& world_from_object) {
    std::vector<Vec3> points;
    points.reserve(mesh.positions.size());
    Vec3 lo{infinity, infinity, infinity}, hi{-infinity, -infinity, -infinity};
    for (const Vec3 p : mesh.positions) {
        points.push_back(world_from_object.point(p));
        lo = min(lo, points.back()), hi = max(hi, points.back());
    }
    // The normal of the largest triangle: the best conditioned.
    Vec3 normal;
    float largest = 0;
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const Vec3 a = points[size_t(mesh.indices[i])], b = points[size_t(mesh.indices[i + 1])],
                   c = points[size_t(mesh.indices[i + 2])];
        const Vec3 n = cross(b - a, c - a);
        if (length(n) > largest) largest = length(n), normal = n;
    }
    if (!(largest > 0)) return std::nullopt;
    normal = normal / largest;
    const Vec3 point = points[size_t(mesh.indices[0])];
    const float tolerance = 1e-5f * (length(hi - lo) + ray_epsilon(point));
    for (const Vec3 p : points)
        if (std::abs(dot(p - point, normal)) > tolerance) return std::nullopt;
    for (const Vec3 n : mesh.normals)
        if (std::abs(dot(normalize(world_from_object.normal(n)), normal)) < 0.99999f) return std::nullopt;
    return MirrorPlane{-1, point, normal};
}

}  // namespace

std::vector<MirrorPlane> flat_mirrors(const Scene& scene, const FrameState& frame) {
    std::vector<MirrorPlane> mirrors;
    for (const int object : scene.static_objects()) {
        const ObjectDesc& desc = scene.object(object);
        const TriangleMesh* mesh = std::get_if<TriangleMesh>(&desc.geometry);
        if (!mesh || desc.is_emitter() || scene.desc().materials[size_t(desc.material)].type != MaterialType::mirror)
            continue;
        if (std::optional<MirrorPlane> plane = plane_of(*mesh, frame.world_from_object[size_t(object)])) {
            plane->object = object;
            mirrors.push_back(*plane);
        }
    }
    return mirrors;
}

}  // namespace steadylight
