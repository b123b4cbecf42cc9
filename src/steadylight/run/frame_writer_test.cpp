#include "steadylight/run/frame_writer.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <thread>
#include <vector>

namespace steadylight {
namespace {

// Frames are reported written in order, on the caller's thread, once their write is done; the
// next frame's write starts only after the previous one finished.
TEST(FrameWriter, WritesInOrderAndReportsOnTheCallersThread) {
    std::vector<int> written, writes;
    const std::thread::id caller = std::this_thread::get_id();
    FrameWriter writer([&](int frame) {
        EXPECT_EQ(std::this_thread::get_id(), caller);
        written.push_back(frame);
    });
    for (int frame = 0; frame < 5; ++frame) writer.write(frame, [&writes, frame] { writes.push_back(frame); });
    writer.finish();
    EXPECT_EQ(writes, (std::vector<int>{0, 1, 2, 3, 4}));
    EXPECT_EQ(written, (std::vector<int>{0, 1, 2, 3, 4}));
}

// A failed write (a full disk) is rethrown at the next write, and its frame is not reported.
TEST(FrameWriter, AFailedWriteIsRethrownAndNotReported) {
    std::vector<int> written;
    FrameWriter writer([&](int frame) { written.push_back(frame); });
    writer.write(0, [] {});
    writer.write(1, [] { throw std::runtime_error("disk full"); });
    EXPECT_THROW(writer.write(2, [] {}), std::runtime_error);
    writer.finish();
    EXPECT_EQ(written, (std::vector<int>{0}));
}

// While another error leaves (Ctrl-C), the pending frame is still written and reported, and a
// failure of its own does not escape.
TEST(FrameWriter, FinishQuietlyWritesThePendingFrameAndSwallowsItsError) {
    std::vector<int> written;
    FrameWriter writer([&](int frame) { written.push_back(frame); });
    writer.write(7, [] {});
    writer.finish_quietly();
    EXPECT_EQ(written, (std::vector<int>{7}));
    writer.write(8, [] { throw std::runtime_error("disk full"); });
    EXPECT_NO_THROW(writer.finish_quietly());
    EXPECT_EQ(written, (std::vector<int>{7}));
}

}  // namespace
}  // namespace steadylight
