// Wall-clock time of a piece of work, in seconds: frame phases (passes/frame_stats.h), whole
// frames and runs (render.cpp), benchmarks.
#pragma once

#include <chrono>

namespace steadylight {

/// Measures wall time from its construction: `const Stopwatch w; ...; seconds = w.elapsed_s();`
class Stopwatch {
public:
    double elapsed_s() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    }

private:
    std::chrono::steady_clock::time_point m_start = std::chrono::steady_clock::now();
};

}  // namespace steadylight
