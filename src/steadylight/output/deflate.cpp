#include "steadylight/output/deflate.h"

#include <isa-l/igzip_lib.h>
#include <zlib.h>

#include <cstdint>
#include <limits>

namespace steadylight {

bool append_deflated(const unsigned char* data, size_t size, size_t max_size, std::vector<unsigned char>& out) {
    if (size > std::numeric_limits<uint32_t>::max() || max_size > std::numeric_limits<uint32_t>::max())
        return false;  // igzip counts in 32 bits; no block of ours comes near
    // Fresh zeroed working memory for every stream, for the level and for the output: the same
    // data must give the same bytes whatever the thread compressed before, since frames rendered
    // by different processes are compared byte for byte (the farm's tests).
    std::vector<uint8_t> level_buffer(ISAL_DEF_LVL1_DEFAULT);
    const size_t start = out.size();
    out.resize(start + max_size);
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
    stream.next_out = out.data() + start;
    stream.avail_out = uint32_t(max_size);
    const bool fits = isal_deflate_stateless(&stream) == COMP_OK;  // else longer than max_size
    out.resize(fits ? start + stream.total_out : start);
    return fits;
}

size_t deflate_zlib_bound(size_t size) { return compressBound(uLong(size)); }

}  // namespace steadylight
