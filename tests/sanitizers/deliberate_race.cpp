// A data race on purpose, in our own parallel loop (base/parallel.h, over oneTBB): every chunk
// adds to one plain counter. The thread-sanitizer build runs it as the test
// sanitizer.thread_reports_our_races, which passes only when ThreadSanitizer reports the race, so
// that the suppressions (thread_suppressions.txt) can never hide races in our own code.
#include <cstdio>

#include "steadylight/base/parallel.h"

int main() {
    long counter = 0;
    for (int round = 0; round < 100; ++round)
        steadylight::parallel_for_chunks(1 << 16, 64, [&](long begin, long end) { counter += end - begin; });
    std::printf("counted %ld\n", counter);
    return 0;
}
