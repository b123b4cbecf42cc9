#include "steadylight/output/deflate.h"

#include <isa-l/igzip_lib.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <limits>

namespace steadylight {

bool append_deflated(const unsigned char* data, size_t size, size_t max_size, std::vector<unsigned char>& out) {
    if (size > std::numeric_limits<uint32_t>::max() || max_size > std::numeric_limits<uint32_t>::max())
        return false;  // igzip counts in 32 bits; no block of ours comes near
    // The level's working memory and the stream's, kept by each thread that compresses, and
    // zeroed for each stream as a fresh thread's are: a frame written by a process that had
    // compressed other files before once held a block whose bytes differed (inflating to the
    // same data) from the same frame's written by another process, and frames must come out
    // the same bytes wherever they are rendered (the farm's tests compare them).
    thread_local std::vector<uint8_t> level_buffer(ISAL_DEF_LVL1_DEFAULT);
    thread_local std::vector<uint8_t> stream_buffer;
    std::fill(level_buffer.begin(), level_buffer.end(), uint8_t(0));
    stream_buffer.assign(max_size, 0);
    isal_zstream stream;
    isal_deflate_stateless_init(&stream);
    stream.level = 1;
    stream.level_buf = level_buffer.data();
    stream.level_buf_size = uint32_t(level_buffer.size());
    stream.gzip_flag = IGZIP_ZLIB;
    stream.end_of_stream = 1;
    stream.flush = NO_FLUSH;
    stream.next_in = const_cast<uint8_t*>(data);
    stream.avail_in = uint32_t(size);
    stream.next_out = stream_buffer.data();
    stream.avail_out = uint32_t(max_size);
    if (isal_deflate_stateless(&stream) != COMP_OK) return false;  // longer than max_size
    out.insert(out.end(), stream_buffer.begin(), stream_buffer.begin() + stream.total_out);
    return true;
}

size_t deflate_zlib_bound(size_t size) { return compressBound(uLong(size)); }

}  // namespace steadylight
