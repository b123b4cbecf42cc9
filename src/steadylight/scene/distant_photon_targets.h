// Where the photons of suns and the world go when no portal says: an interior lit through a
// window it does not mark, or an outdoor scene much larger than what the camera sees. Photons
// from far away start on a disc covering the whole scene (shading/distant_lights.cpp); most of
// them would strike the outside of a room's walls, or ground the camera never sees.
//
// The targets are found from the camera's side: rays from the surfaces the camera sees that
// leave the scene show where light from far away comes in and which way it travels. For each
// travel direction (bins of an octahedral map of the sphere), the disc is divided into cells,
// and the cells such a ray crosses (with their neighbours) are marked. A photon of that
// direction then starts in a marked cell three times in four, else anywhere on the disc, and its
// power divides by the density of both together, so that no light is lost: a photon that could
// reach the scene from a cell nobody marked still can, only less often. The marks depend on the
// scene and the camera alone (fixed rays, no thread order), so every process finds the same.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "steadylight/base/bounding_sphere.h"
#include "steadylight/base/vec.h"

namespace steadylight {

class DistantPhotonTargets {
public:
    /// The targets that photons travelling d through point p would hit, for each (d, p) of
    /// `crossings` (d unit, the way the light travels), over the disc covering `scene`.
    DistantPhotonTargets(const BoundingSphere& scene, const std::vector<std::pair<Vec3, Vec3>>& crossings);

    /// Where a photon travelling unit `d` starts: just outside the scene on the disc facing it,
    /// and the density of that start by area on the disc.
    struct Start {
        Vec3 p;
        float pdf = 0;
    };
    Start sample_start(Vec3 d, Vec2 u) const;

    /// Cells marked over all bins (for logs and tests).
    size_t marked_cells() const;
    uint64_t hash() const;

private:
    int bin_of(Vec3 d) const;
    /// Coordinates of p in the disc's plane for direction d, about the scene's centre.
    Vec2 plane_coordinates(Vec3 d, Vec3 p) const;
    int cell_of(Vec2 xy) const;  // -1 outside the grid

    BoundingSphere m_scene;
    float m_radius = 1;
    std::vector<std::vector<uint8_t>> m_marks;  // per bin: per cell, marked or not
    std::vector<std::vector<int>> m_marked;     // per bin: the marked cells, in index order
};

}  // namespace steadylight
