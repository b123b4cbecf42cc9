// Image (image.h) over its allocator (unfilled_allocator.h): black where made black, whatever
// its memory held before.
#include "steadylight/base/image.h"

#include <gtest/gtest.h>

#include "support/freed_blocks.h"

namespace steadylight {
namespace {

TEST(Image, BlackImagesAreBlackInMemoryThatHeldOtherValues) {
    testing::leave_in_freed_blocks(64 * 48, 3);
    const Image image(64, 48);
    for (const Rgb& c : image.pixels) ASSERT_TRUE(c.r == 0 && c.g == 0 && c.b == 0);
}

// A copy holds the same values, made from them (not left unfilled).
TEST(Image, CopiesHoldTheSameValues) {
    Image image(5, 3);
    image.at(4, 2) = {1, 2, 3};
    testing::leave_in_freed_blocks(15, 7);
    const Image copy = image;
    EXPECT_EQ(copy.pixels, image.pixels);
}

}  // namespace
}  // namespace steadylight
