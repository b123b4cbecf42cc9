// Checkpoints: phases and parallel loops report progress, and an interrupt stops them.
#include "steadylight/base/checkpoint.h"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <vector>

#include "steadylight/base/parallel.h"

namespace steadylight {
namespace {

struct Recorder final : CheckpointListener {
    std::vector<std::string> phases;
    std::atomic<long> last_total = 0, calls = 0;
    void phase(std::string_view name) override { phases.emplace_back(name); }
    void work(long, long total) override { last_total = total, ++calls; }
};

TEST(Checkpoint, PhasesAndLoopsReportToTheListener) {
    Recorder recorder;
    {
        const ScopedCheckpointListener listening(&recorder);
        begin_phase("photons");
        parallel_for_chunks(100, 10, [](long, long) {});
        parallel_for_tiles(64, 32, 16, [](int, int, int, int) {});
    }
    begin_phase("not heard");
    EXPECT_EQ(recorder.phases, std::vector<std::string>{"photons"});
    EXPECT_EQ(recorder.calls, 10 + 8);
    EXPECT_EQ(recorder.last_total, 8);
}

TEST(Checkpoint, InterruptStopsPhasesAndParallelLoops) {
    request_interrupt();
    EXPECT_THROW(begin_phase("shading"), RenderInterrupted);
    std::atomic<int> ran = 0;
    EXPECT_THROW(parallel_for_chunks(1000, 1, [&](long, long) { ++ran; }), RenderInterrupted);
    EXPECT_EQ(ran, 0);
    EXPECT_THROW(parallel_for_tiles(64, 64, 8, [&](int, int, int, int) { ++ran; }), RenderInterrupted);
    EXPECT_EQ(ran, 0);
    clear_interrupt();
    EXPECT_NO_THROW(begin_phase("shading"));
    parallel_for_chunks(10, 1, [&](long, long) { ++ran; });
    EXPECT_EQ(ran, 10);
}

}  // namespace
}  // namespace steadylight
