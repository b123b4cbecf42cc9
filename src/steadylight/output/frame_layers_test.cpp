// A frame's layers (frame_layers.cpp): every channel value finite when written.
#include "steadylight/output/frame_layers.h"

#include <gtest/gtest.h>

#include <limits>

namespace steadylight {
namespace {

TEST(FrameLayers, NonFiniteValuesAreWrittenAsZeroAndReported) {
    Image beauty(4, 3);
    beauty.at(1, 1) = {0.5f, 2, 3};
    std::vector<NamedImage> aovs{{"direct", Image(4, 3)}, {"influence", Image(4, 3), true}};
    EXPECT_EQ(replace_non_finite(beauty, aovs).count, 0);

    aovs[1].image.at(2, 1).r = std::numeric_limits<float>::quiet_NaN();
    aovs[1].image.at(3, 2) = {std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(), 1};
    aovs[0].image.at(3, 0).g = 1e30f;  // finite: kept (the half writer clamps it)
    const NonFiniteValues found = replace_non_finite(beauty, aovs);
    EXPECT_EQ(found.count, 3);
    EXPECT_EQ(found.first_layer, "influence");
    EXPECT_EQ(found.first_x, 2);
    EXPECT_EQ(found.first_y, 1);
    EXPECT_EQ(aovs[1].image.at(2, 1).r, 0);
    EXPECT_EQ(aovs[1].image.at(3, 2).r, 0);
    EXPECT_EQ(aovs[1].image.at(3, 2).g, 0);
    EXPECT_EQ(aovs[1].image.at(3, 2).b, 1);
    EXPECT_EQ(aovs[0].image.at(3, 0).g, 1e30f);
    EXPECT_EQ(beauty.at(1, 1).g, 2);
    EXPECT_EQ(replace_non_finite(beauty, aovs).count, 0);
}

}  // namespace
}  // namespace steadylight
