// Invariant checks that abort with file:line. For programming errors only; user errors are
// InputError. SL_DCHECK compiles away in release builds.
#pragma once

#include <cstdio>
#include <cstdlib>

#define SL_CHECK(cond)                                                                    \
    do {                                                                                  \
        if (!(cond)) {                                                                    \
            std::fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
            std::abort();                                                                 \
        }                                                                                 \
    } while (0)

#define SL_CHECK_EQ(a, b) SL_CHECK((a) == (b))

#ifdef NDEBUG
#define SL_DCHECK(cond) ((void)0)
#else
#define SL_DCHECK(cond) SL_CHECK(cond)
#endif
