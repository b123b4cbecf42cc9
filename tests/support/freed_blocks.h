// Test helper: memory a test's next allocations are likely to take, left holding known values,
// to show a value read where nothing was written (base/unfilled_allocator.h).
#pragma once

#include <vector>

#include "steadylight/base/color.h"

namespace steadylight::testing {

/// Leaves `value` in freed heap blocks of `pixels` colours, so that the next arrays of that size
/// are likely made in memory that holds it.
inline void leave_in_freed_blocks(size_t pixels, float value) {
    std::vector<std::vector<Rgb>> blocks(32, std::vector<Rgb>(pixels, Rgb{value, value, value}));
    for (std::vector<Rgb>& block : blocks) asm volatile("" : : "r"(block.data()) : "memory");  // kept, filled
}

}  // namespace steadylight::testing
