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
// reach the scene from a cell nobody marked still can, only less often. A light that chooses its
// photons' directions (the world) may also take them from the marked bins (AimedDirections). The
// marks depend on the scene and the camera alone (fixed rays, no thread order), so every process
// finds the same.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "steadylight/base/bounding_sphere.h"
#include "steadylight/base/distribution_2d.h"
#include "steadylight/base/vec.h"

namespace steadylight {

/// Travel directions for the photons of a light that may choose them (the world, whose image
/// may be brightest where no opening looks): a direction bin with marks in proportion to the
/// light its marked cells let in, then uniformly over the bin's square of the octahedral map.
class AimedDirections {
public:
    struct Sample {
        Vec3 d;         // unit, the way the photon travels
        float pdf = 0;  // by solid angle
    };
    Sample sample(Vec2 u) const;
    /// The density by solid angle of travelling unit `d`: zero in a bin without marks.
    float pdf(Vec3 d) const;

private:
    friend class DistantPhotonTargets;
    explicit AimedDirections(Distribution1D bins) : m_bins(std::move(bins)) {}
    Distribution1D m_bins;  // over the octahedral map's bins, row-major
};

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

    /// Directions for photons that travelling d carry light of luminance `luminance(d)`: the
    /// marked bins, each in proportion to its light times its marked cells; none without marks
    /// (or where the light is black in every marked bin).
    std::optional<AimedDirections> aimed_directions(const std::function<float(Vec3)>& luminance) const;

    /// Cells marked over all bins (for logs and tests).
    size_t marked_cells() const;
    uint64_t hash() const;

private:
    /// Coordinates of p in the disc's plane for direction d, about the scene's centre.
    Vec2 plane_coordinates(Vec3 d, Vec3 p) const;
    /// The grid's column and row that hold xy (outside [0, cells) beyond the grid).
    std::pair<int, int> grid_cell(Vec2 xy) const;
    int cell_of(Vec2 xy) const;  // -1 outside the grid

    BoundingSphere m_scene;
    float m_radius = 1;
    std::vector<std::vector<uint8_t>> m_marks;  // per bin: per cell, marked or not
    std::vector<std::vector<int>> m_marked;     // per bin: the marked cells, in index order
};

}  // namespace steadylight
