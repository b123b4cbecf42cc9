// Pixel reuse for a still camera (issue 12, point 2; docs/localized.md, "Pixels reused"). A
// segment whose camera and lights do not move keeps a static frame: every pixel shaded with the
// dynamic objects removed, its per-term sums and what its shading went through (shading_pass.h
// StaticFrame). Each frame then asks, per pixel and conservatively, which terms the frame's
// changes can reach, and does only that work:
//   camera  a camera ray may meet a dynamic object (the object's screen box), or a chain of
//           mirror and glass bounces may (the sphere about the pixel's points)
//   direct  a shadow ray may: a dynamic object's sphere meets the hull of the pixel's points and
//           a light
//   indirect  a corrected static record whose reach covers the pixel's screen position changed,
//           the influence blends in L_y, or the pixel gathered anew or read photons (a coat)
//   caustic a caustic photon that changed lies within an estimate's reach of the pixel on the
//           screen (or the caustic map changed whole) and the pixel shaded a diffuse point
// No bit: the pixel is the static frame's, bit for bit what shading it would give. Only the
// indirect bit, from changed records alone: its indirect light is looked up again where its
// camera rays looked it up in the static frame, no ray traced. Only the indirect or caustic
// bits: it is shaded again without its shadow rays (its direct light is the static frame's).
// Else it is shaded again whole. Points seen through mirrors and glass are not
// on the screen where their pixel is, so a pixel with chains counts as changed whenever a record
// or a caustic photon changed anywhere.
#pragma once

#include <cstdint>
#include <vector>

#include "steadylight/base/bounding_sphere.h"
#include "steadylight/passes/shading_pass.h"

namespace steadylight {

/// The bits of the `changed` layer: which terms of a pixel a frame redid.
enum ChangedTerm : uint8_t { camera_term = 1, direct_term = 2, indirect_term = 4, caustic_term = 8 };

/// What changed in a frame against its static frame.
struct FrameChanges {
    std::vector<BoundingSphere> dynamic;  // the dynamic objects at this frame
    std::vector<BoundingSphere> lights;
    enum IndirectChange : uint8_t { records = 1, blend = 2 };
    std::vector<uint8_t> indirect;  // per pixel, row by row: IndirectChange bits, why its indirect light may change
    bool records_changed = false;   // some corrected record differs from the static one
    bool caustics_changed = false;  // the caustic map differs from the static one somewhere
    std::vector<uint8_t> caustic;   // per pixel: a diffuse point there may read changed caustic photons
};

/// The work of every pixel of a frame, the terms that made it, and how many of each.
struct PixelPlan {
    std::vector<PixelWork> work;
    std::vector<uint8_t> changed;  // ChangedTerm bits
    long reused = 0, looked_up_again = 0, redone_but_direct = 0, redone = 0;
    long changed_pixels[4] = {};  // per ChangedTerm bit, in bit order
};

PixelPlan plan_pixels(const Camera& camera, const StaticFrame& base, const FrameChanges& changes);

/// How closely mark_sphere_on_screen() follows a sphere: its screen box (cheap: for many small
/// spheres), or within the box the pixels whose centre's ray comes within the sphere's angular
/// radius plus half a pixel's diagonal of its centre (a ray per pixel: for a few large ones).
enum class Outline { box, round };

/// Sets `mask` at every pixel whose camera rays may pass through `sphere` (the whole screen when
/// it reaches behind the camera).
void mark_sphere_on_screen(const Camera& camera, const BoundingSphere& sphere, std::vector<uint8_t>& mask,
                           Outline outline = Outline::box);

/// Whether a frame of `scene` at `frame` may reuse pixels of a static frame made at `static_frame`
/// of the same segment: the same camera, lights and emissions, and no dynamic object emits.
bool same_view_and_lights(const Scene& scene, const FrameState& frame, const FrameState& static_frame);

}  // namespace steadylight
