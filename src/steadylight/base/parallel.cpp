#include "steadylight/base/parallel.h"

#include <pmmintrin.h>
#include <xmmintrin.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>

#include "steadylight/base/checkpoint.h"

namespace steadylight {

void set_render_thread_fp_modes() {
    // Embree's own recommendation: denormals slow traversal badly.
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

void parallel_for_tiles(int width, int height, int tile_size, const std::function<void(int, int, int, int)>& body) {
    const int tiles_x = (width + tile_size - 1) / tile_size;
    const int tiles_y = (height + tile_size - 1) / tile_size;
    const int tiles = tiles_x * tiles_y;
    std::atomic<int> done = 0;
    // An interrupt skips the remaining tiles: TBB cancels the loop and rethrows here.
    tbb::parallel_for(
        0, tiles,
        [&](int tile) {
            throw_if_interrupted();
            set_render_thread_fp_modes();
            const int x0 = (tile % tiles_x) * tile_size, y0 = (tile / tiles_x) * tile_size;
            body(x0, y0, std::min(x0 + tile_size, width), std::min(y0 + tile_size, height));
            report_work(++done, tiles);
        },
        tbb::simple_partitioner());
}

void parallel_for_chunks(long count, long chunk_size, const std::function<void(long, long)>& body) {
    const long chunks = (count + chunk_size - 1) / chunk_size;
    std::atomic<long> done = 0;
    tbb::parallel_for(
        0L, chunks,
        [&](long chunk) {
            throw_if_interrupted();
            set_render_thread_fp_modes();
            body(chunk * chunk_size, std::min(count, (chunk + 1) * chunk_size));
            report_work(++done, chunks);
        },
        tbb::simple_partitioner());
}

}  // namespace steadylight
