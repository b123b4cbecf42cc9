// Large blocks kept in the heap (freed_memory.cpp). A frame allocates and frees the same large
// arrays every frame (TABLE's composed global photon map alone is about 47 MB). glibc serves
// blocks above its mmap threshold with fresh mappings and hands freed ones, and the heap's free
// top, back to the system, so every frame faulted its arrays in again page by page, each page
// zeroed by the kernel: on the 2-core VM a 48 MB block cost 0.2 s to fault in, and TABLE's photon
// phase took 0.56 s a frame instead of 0.23 s. Kept in the heap, the next frame reuses the
// same pages. The resident set then stays at the largest a frame reached (which every frame
// reaches anyway) instead of shrinking between frames.
#pragma once

namespace steadylight {

/// Serves large blocks from the heap and keeps freed memory mapped for the next allocation.
/// Call once, at the start of a program that renders frames.
void keep_freed_memory_mapped();

}  // namespace steadylight
