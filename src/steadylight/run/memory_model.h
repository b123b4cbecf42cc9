// What a render needs in memory, estimated before any work from the image size, the photon counts,
// the scene's triangles and its world image, against what this process may use: a render that
// cannot fit stops at once with the figure and the option to lower, not with an out-of-memory kill
// an hour later. The model (docs/usage.md, "Memory"), measured by peak resident size on BALL and
// the 2.1-million-triangle terrain, rounded up: a fixed 64 MB (the program, its libraries, the
// scene's small parts); 160 bytes per triangle (the mesh and Embree's BVH; measured 150); per pixel
// 300 bytes for the photon method (the frame's layers, the cache's pixel bookkeeping, a frame's
// layers held while the next renders; measured 250), 540 for the localized and frozen methods (a
// dozen layers, the still-camera static frame; measured 490; and up to 40 for its kept light
// samples, passes/kept_direct_light.h) and 60 for the path tracer (measured 25); 650 bytes per
// photon path emitted (global and caustic: stored photons, their kd-trees, the precomputed
// irradiance, the static paths kept for reuse and the frame's composed maps; measured 580 on BALL
// from 800,000 to 3.2 million, more in brighter rooms whose paths are longer); 48 bytes per pixel
// of a world image (measured 41 on the courtyard: the image, its two sampling tables, the EXR
// decoder's buffers). The static frame is counted at its usual size; one that would outgrow its
// share of what is available is not kept (pixel_reuse.h static_frame_memory_share).
#pragma once

#include <cstddef>
#include <string>

#include "steadylight/run/render_settings.h"
#include "steadylight/scene/scene.h"

namespace steadylight {

struct MemoryEstimate {
    double scene = 0, pixels = 0, photons = 0;  // bytes, beside the fixed part
    double total() const;
};

/// What rendering `scene` (at its final size) with `settings` needs.
MemoryEstimate estimate_memory(const RenderSettings& settings, const Scene& scene);

/// What this process may use, and where that limit comes from: the cgroup's limit (v2 or v1),
/// Slurm's (SLURM_MEM_PER_NODE, or SLURM_MEM_PER_CPU times SLURM_CPUS_ON_NODE), whichever is
/// smallest, else the machine's physical memory.
struct MemoryLimit {
    size_t bytes = 0;
    std::string source;
};
MemoryLimit memory_available();

/// Throws InputError when the estimate exceeds `limit`, saying how much it would need, how much
/// there is and which option to lower (the largest part's).
void check_memory(const MemoryEstimate& need, const MemoryLimit& limit);

/// Triangles of every mesh of the scene.
long triangle_count(const SceneDesc& desc);

}  // namespace steadylight
