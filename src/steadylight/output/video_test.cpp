// Tests for the ffmpeg command of `--video` (video.h). The encoding itself is checked end to
// end by tests/cli/video.sh, which needs ffmpeg and ffprobe.
#include "steadylight/output/video.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace steadylight {
namespace {

/// The value that follows `flag` in `arguments`, or "" when the flag is absent.
std::string value_of(const std::vector<std::string>& arguments, const std::string& flag) {
    const auto it = std::find(arguments.begin(), arguments.end(), flag);
    return it == arguments.end() || it + 1 == arguments.end() ? "" : *(it + 1);
}

TEST(Video, ContiguousSpanNeedsConsecutiveFrames) {
    EXPECT_EQ(contiguous_span({4, 5, 6}), (std::pair{4, 6}));
    EXPECT_EQ(contiguous_span({7}), (std::pair{7, 7}));
    EXPECT_FALSE(contiguous_span({}));
    EXPECT_FALSE(contiguous_span({1, 3, 5}));
    EXPECT_FALSE(contiguous_span({2, 1}));
}

TEST(Video, ArgumentsEncodeH264Yuv420pAtTheSceneRateFromTheFirstFrame) {
    const VideoJob job{.out_dir = "my out",
                       .scene_name = "ball",
                       .first_frame = 12,
                       .frame_count = 3,
                       .fps = 29.97f,
                       .output = "x.mp4"};
    const std::vector<std::string> arguments = ffmpeg_arguments(job, "x.mp4.partial");
    EXPECT_EQ(value_of(arguments, "-c:v"), "libx264");
    EXPECT_EQ(value_of(arguments, "-pix_fmt"), "yuv420p");
    EXPECT_EQ(value_of(arguments, "-framerate"), "29.97");
    EXPECT_EQ(value_of(arguments, "-start_number"), "12");
    EXPECT_EQ(value_of(arguments, "-frames:v"), "3");
    EXPECT_EQ(value_of(arguments, "-i"), "my out/ball_%04d.png");  // one argument: no shell quoting
    EXPECT_EQ(arguments.back(), "x.mp4.partial");
    EXPECT_NE(std::find(arguments.begin(), arguments.end(), "-y"), arguments.end());
}

TEST(Video, PercentSignsInNamesAreEscapedForFfmpegsPattern) {
    const VideoJob job{.out_dir = "100%", .scene_name = "a%d", .frame_count = 1};
    EXPECT_EQ(value_of(ffmpeg_arguments(job, "v"), "-i"), "100%%/a%%d_%04d.png");
}

TEST(Video, OddSizesArePaddedToEven) {
    const std::string filter = value_of(ffmpeg_arguments({.frame_count = 1}, "v"), "-vf");
    EXPECT_NE(filter.find("pad=ceil(iw/2)*2:ceil(ih/2)*2"), std::string::npos);
    EXPECT_EQ(filter.find("premultiply"), std::string::npos);
}

TEST(Video, PngsWithAlphaAreLaidOverBlack) {
    const std::string filter = value_of(ffmpeg_arguments({.frame_count = 1, .alpha = true}, "v"), "-vf");
    EXPECT_EQ(filter.rfind("premultiply=inplace=1,", 0), 0u);  // first, before the padding
}

}  // namespace
}  // namespace steadylight
