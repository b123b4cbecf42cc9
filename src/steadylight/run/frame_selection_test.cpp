// `--frames` parsing: valid lists, and errors that name the option and the bad part.
#include "steadylight/run/frame_selection.h"

#include <gtest/gtest.h>

#include "steadylight/base/error.h"
#include "support/input_error.h"

namespace steadylight {
namespace {

std::vector<int> frames_of(const std::string& text, int frame_count = 100) {
    return select_frames(parse_frame_selection(text), frame_count);
}

/// The InputError message for `text`, or "" when it parses and fits 100 frames.
std::string error_of(const std::string& text) {
    return testing::input_error_of([&] { frames_of(text); });
}

TEST(FrameSelection, NoSpansSelectsEveryFrame) { EXPECT_EQ(select_frames({}, 4), (std::vector<int>{0, 1, 2, 3})); }

TEST(FrameSelection, SingleFrameRangeAndStep) {
    EXPECT_EQ(frames_of("7"), (std::vector<int>{7}));
    EXPECT_EQ(frames_of("3-6"), (std::vector<int>{3, 4, 5, 6}));
    EXPECT_EQ(frames_of("10-20:2"), (std::vector<int>{10, 12, 14, 16, 18, 20}));
    EXPECT_EQ(frames_of("10-21:5"), (std::vector<int>{10, 15, 20}));
    EXPECT_EQ(frames_of("0-59"), frames_of("0-59:1"));
}

TEST(FrameSelection, ListsAreSortedWithoutDuplicates) {
    EXPECT_EQ(frames_of("1,5,10-20:5"), (std::vector<int>{1, 5, 10, 15, 20}));
    EXPECT_EQ(frames_of("20, 3-5 ,4,3"), (std::vector<int>{3, 4, 5, 20}));
    EXPECT_EQ(frames_of(" 8 - 9 : 1 "), (std::vector<int>{8, 9}));
}

TEST(FrameSelection, BadTextNamesTheOptionAndThePart) {
    for (const char* text : {"", "x", "1,", ",1", "1,,2", "-3", "3-", "1-2-3", "1:2", "1.5", "1-5:", "1234567890"}) {
        const std::string message = error_of(text);
        EXPECT_NE(message.find("--frames"), std::string::npos) << text;
        EXPECT_NE(message.find("expected N, A-B"), std::string::npos) << text << ": " << message;
    }
    EXPECT_NE(error_of("1,x7,3").find("\"x7\""), std::string::npos);
}

TEST(FrameSelection, ReversedRangeAndZeroStepAreErrors) {
    EXPECT_NE(error_of("9-3").find("\"9-3\": the range ends before it starts"), std::string::npos);
    EXPECT_NE(error_of("1,3-9:0").find("\"3-9:0\": the step must be at least 1"), std::string::npos);
}

TEST(FrameSelection, FramesPastTheSceneAreErrors) {
    EXPECT_EQ(frames_of("59", 60), (std::vector<int>{59}));
    try {
        frames_of("1,50-60:5", 60);
        FAIL() << "expected an InputError";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "--frames: frame 60 is past the scene's last frame 59 (in \"50-60:5\")");
    }
}

TEST(FrameSelection, FormatRoundTrips) {
    EXPECT_EQ(format_frame_list({}), "");
    EXPECT_EQ(format_frame_list({0, 1, 2, 5, 7, 8}), "0-2,5,7-8");
    const std::vector<int> frames = frames_of("1,5,10-20:5,30-40");
    EXPECT_EQ(frames_of(format_frame_list(frames)), frames);
}

}  // namespace
}  // namespace steadylight
