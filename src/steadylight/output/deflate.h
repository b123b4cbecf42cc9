// zlib streams (RFC 1950) for the files steadylight writes: the EXR's ZIP blocks and the PNG's
// pixels, deflated by ISA-L's igzip at its level 1. On a 1280x960 frame's 18 half channels it
// takes a fifth of the time of zlib's own fastest level (51 ms against 250 ms on one core) into
// files 6% smaller; a frame is written beside the next one's rendering, and on few cores its
// compression took a fifth of a localized frame's CPU (docs/notes/frame-cost.md, step 17).
// Any inflate reads the streams back to the same bytes. The compressed bytes themselves may
// differ between processors, since igzip picks its code by the instruction sets it finds.
#pragma once

#include <cstddef>
#include <vector>

namespace steadylight {

/// Appends `size` bytes from `data` to `out` as a zlib stream, if that is at most `max_size` bytes
/// long, and returns true; else leaves `out` as it was and returns false. The same data gives the
/// same bytes whatever the thread compressed before.
bool append_deflated(const unsigned char* data, size_t size, size_t max_size, std::vector<unsigned char>& out);

/// The longest zlib stream append_deflated may need for `size` bytes (its stored blocks' worst case).
size_t deflate_zlib_bound(size_t size);

}  // namespace steadylight
