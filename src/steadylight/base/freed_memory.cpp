#include "steadylight/base/freed_memory.h"

#include <cstdlib>  // defines __GLIBC__ under glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace steadylight {

void keep_freed_memory_mapped() {
#if defined(__GLIBC__)
    constexpr int one_gib = 1 << 30;
    mallopt(M_MMAP_THRESHOLD, one_gib);  // fixed: no longer raised as blocks are freed
    mallopt(M_TRIM_THRESHOLD, one_gib);
#endif
}

}  // namespace steadylight
