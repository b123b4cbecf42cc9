// The renderer's parallel loops, over oneTBB. Work is split by index only, so results never
// depend on how many threads run or how TBB schedules them. Each tile or chunk is a task of its
// own (TBB's simple partitioner): the default groups them into ranges that are split only when a
// thread steals, and a loop then ends with one thread working through a range of costly tiles,
// such as a localized frame's last rows under a moving object, while the others wait. Every tile
// and chunk is a checkpoint (base/checkpoint.h): it reports progress, and after an interrupt the
// loop throws RenderInterrupted instead of running the rest.
#pragma once

#include <functional>

namespace steadylight {

/// Calls `body(x0, y0, x1, y1)` for every tile of a width x height image, in parallel.
void parallel_for_tiles(int width, int height, int tile_size, const std::function<void(int, int, int, int)>& body);

/// Calls `body(begin, end)` over chunks of [0, count), in parallel.
void parallel_for_chunks(long count, long chunk_size, const std::function<void(long, long)>& body);

/// Sets the floating-point modes Embree wants (flush-to-zero, denormals-are-zero) on this thread.
void set_render_thread_fp_modes();

}  // namespace steadylight
