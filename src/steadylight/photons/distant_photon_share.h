// How many of the photons of light from far away (suns, the world) reach what the camera sees.
// They start outside the scene and, in an interior lit through windows, most of them would strike
// the outside of its walls unless portals aim them (shading/distant_lights.cpp): the share of
// distant-light photon paths whose first hit is on a surface side the camera path sees says how
// well they are aimed (stats.json's `distant_photons_inside`).
//
// "Seen" is measured, not derived: a grid of camera rays at frames spread over the animation,
// the static objects only (the dynamic ones count as seen, sides and all: they move among what
// the camera sees). A side is a triangle's (or a sphere's) front or back as the ray meets it, so
// the outer face of a wall is not its inner face. Small triangles between the grid's rays can be
// missed: the share is an estimate, good for telling aimed photons from wasted ones.
//
// The same view of the camera aims the photons when the scene has no portals
// (aim_distant_photons).
#pragma once

#include <cstdint>
#include <optional>
#include <unordered_set>

#include "steadylight/shading/frame_context.h"

namespace steadylight {

/// The surface sides the camera sees over the animation.
class CameraSeenSides {
public:
    /// Traces `columns` x `rows` camera rays at up to `max_frames` frames evenly spread over the
    /// animation, against the static objects of `tracer` (placed anywhere).
    CameraSeenSides(const Scene& scene, const RayTracer& tracer, int columns = 96, int rows = 72, int max_frames = 48);

    /// Whether the side of `hit` that `ray` meets is seen.
    bool seen(const Scene& scene, const FrameState& frame, const Ray& ray, const Hit& hit) const;

private:
    static uint64_t key(int object, int primitive, bool front);
    std::unordered_set<uint64_t> m_seen;
};

/// Aims the photons of light from far away (scene/distant_photon_targets.h) when the scene has
/// such light and no portals: from the static surfaces a grid of camera rays sees at frames
/// spread over the animation, rays in cosine-weighted directions and towards each sun; those that
/// leave the scene mark where light from that way comes in. The number of cells marked, or
/// nothing when the scene needs no aiming.
std::optional<size_t> aim_distant_photons(Scene& scene);

/// The share of `paths` photon paths from the context's lights from far away whose first hit is
/// a side `seen` holds (in [0, 1]); nothing when the frame has no light from far away.
std::optional<double> distant_photons_inside(const FrameContext& context, const CameraSeenSides& seen,
                                             long paths = 1 << 14);

}  // namespace steadylight
