// The path tracer: unidirectional path tracing with next-event estimation, multiple importance
// sampling (power heuristic) between BSDF and light sampling for area lights, and Russian
// roulette (Veach 1997; pbrt-v4 PathIntegrator). It is the ground truth the photon-mapping
// methods are checked against. Deterministic: each pixel's random stream is seeded from
// (frame, pixel), so the image does not depend on the thread count. With `fixed_seed` each
// camera sample of a pixel has a stream of its own, seeded from (pixel, sample) and the same in
// every frame: where no path meets a moving object two frames are bit-identical, and elsewhere
// their difference is an unbiased estimate of the true change.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "steadylight/base/image.h"
#include "steadylight/base/rng.h"
#include "steadylight/passes/frame_stats.h"
#include "steadylight/shading/frame_context.h"

namespace steadylight {

struct PathTracerSettings {
    int samples_per_pixel = 64;
    int max_depth = 64;            // bounces; Russian roulette usually ends paths much earlier
    int roulette_start_depth = 3;  // bounces before Russian roulette may end a path
    uint64_t seed = 0;             // another seed gives independent noise (for reference images)
    bool fixed_seed = false;       // the same random numbers per (pixel, camera sample) in every frame
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(PathTracerSettings, samples_per_pixel, max_depth, roulette_start_depth,
                                                seed, fixed_seed)
/// Throws InputError naming `where` + "/<field>" for a value out of range.
void validate(const PathTracerSettings& settings, const std::string& where);

/// Called after each finished tile with (tiles done, tiles in all); may be called concurrently.
using TileProgress = std::function<void(int, int)>;

/// A path-traced frame: the image, and its time, camera samples, rays and path vertices.
struct PathFrame {
    Image beauty;
    /// With a transparent background (Camera::transparent_background): the share of each
    /// pixel's camera samples that met a surface, grey; the beauty is premultiplied by it.
    std::optional<Image> alpha;
    FrameStats stats;
};

PathFrame render_path_traced(const FrameContext& context, const PathTracerSettings& settings,
                             const TileProgress& progress = {});

/// What tracing paths cost: rays traced (closest hits and shadow rays) and path vertices (the
/// surface hits; mean path length = vertices / camera samples). Counting changes no pixel.
struct PathCounts {
    long rays = 0;
    long vertices = 0;
};

/// What a camera ray's path found: the radiance arriving along the ray (from its far end
/// towards its origin), and whether the ray met a surface.
struct PathRadiance {
    Rgb L;
    bool met_surface = false;
};

/// The path from camera ray `ray`; adds its rays and vertices to `counts`. With a transparent
/// background (Camera::transparent_background) the world the ray itself sees is left out; what
/// the path sees of it further on (through glass, in a mirror, as light) stays.
PathRadiance trace_path(const FrameContext& context, Ray ray, Pcg32& rng, const PathTracerSettings& settings,
                        PathCounts& counts);

}  // namespace steadylight
