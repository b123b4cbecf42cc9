// Large blocks kept in the heap (freed_memory.cpp). A frame allocates and frees the same large
// arrays every frame (TABLE's composed global photon map alone is about 47 MB). glibc serves
// blocks above its mmap threshold with fresh mappings and hands freed ones, and the heap's free
// top, back to the system, so every frame would fault its arrays in again page by page, each
// page zeroed by the kernel (a large share of a frame's photon phase: docs/notes/reuse-speed.md).
// Kept in the heap, the next frame reuses the
// same pages. The resident set then stays at the largest a frame reached (which every frame
// reaches anyway) instead of shrinking between frames.
#pragma once

namespace steadylight {

/// Serves large blocks from the heap and keeps freed memory mapped for the next allocation.
/// Call once, at the start of a program that renders frames.
void keep_freed_memory_mapped();

}  // namespace steadylight
