// The progress bar's status line and durations.
#include "steadylight/run/console.h"

#include <gtest/gtest.h>

namespace steadylight {
namespace {

TEST(Console, DurationsReadAsClockTimes) {
    EXPECT_EQ(format_duration(0), "0:00");
    EXPECT_EQ(format_duration(65.4), "1:05");
    EXPECT_EQ(format_duration(3725), "1:02:05");
    EXPECT_EQ(format_duration(-3), "0:00");
}

TEST(Console, StatusLineShowsFramesPhaseAndEta) {
    ConsoleProgress progress(4, false);
    EXPECT_NE(progress.status_line().find("0/4 frames"), std::string::npos);
    EXPECT_NE(progress.status_line().find("ETA ?"), std::string::npos);
    progress.begin_frame(12);
    progress.phase("influence");
    progress.work(1, 4);
    const std::string line = progress.status_line();
    EXPECT_NE(line.find("frame 12: influence 25%"), std::string::npos) << line;
    progress.finish_frame();
    EXPECT_NE(progress.status_line().find("[#####...............] 1/4 frames"), std::string::npos);
    EXPECT_EQ(progress.status_line().find("ETA ?"), std::string::npos);
}

}  // namespace
}  // namespace steadylight
