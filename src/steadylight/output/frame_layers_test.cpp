// A frame's layers (frame_layers.cpp): every channel value finite when written.
#include "steadylight/output/frame_layers.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <variant>

#include "steadylight/output/image_writer.h"

namespace steadylight {
namespace {

TEST(FrameLayers, NonFiniteValuesAreWrittenAsZeroAndReported) {
    Image beauty(4, 3);
    beauty.at(1, 1) = {0.5f, 2, 3};
    std::vector<NamedImage> aovs{{"direct", Image(4, 3)}, {"influence", GreyImage(4, 3)}};
    Image& direct = std::get<Image>(aovs[0].image);
    GreyImage& influence = std::get<GreyImage>(aovs[1].image);
    EXPECT_EQ(replace_non_finite(beauty, aovs).count, 0);

    influence.at(2, 1) = std::numeric_limits<float>::quiet_NaN();
    influence.at(3, 1) = -std::numeric_limits<float>::infinity();
    influence.at(3, 2) = std::numeric_limits<float>::infinity();
    influence.at(0, 2) = 1;
    direct.at(3, 0).g = 1e30f;  // finite: kept (the half writer clamps it)
    const NonFiniteValues found = replace_non_finite(beauty, aovs);
    EXPECT_EQ(found.count, 3);
    EXPECT_EQ(found.first_layer, "influence");
    EXPECT_EQ(found.first_x, 2);
    EXPECT_EQ(found.first_y, 1);
    EXPECT_EQ(influence.at(2, 1), 0);
    EXPECT_EQ(influence.at(3, 1), 0);
    EXPECT_EQ(influence.at(3, 2), 0);
    EXPECT_EQ(influence.at(0, 2), 1);
    EXPECT_EQ(direct.at(3, 0).g, 1e30f);
    EXPECT_EQ(beauty.at(1, 1).g, 2);
    EXPECT_EQ(replace_non_finite(beauty, aovs).count, 0);

    // The first is the first in layer order, the beauty's first of all, then pixel order, and a
    // colour layer's pixel is found by its position whichever channel holds the value.
    influence.at(0, 0) = std::numeric_limits<float>::quiet_NaN();
    direct.at(3, 2).b = std::numeric_limits<float>::infinity();
    const NonFiniteValues in_two = replace_non_finite(beauty, aovs);
    EXPECT_EQ(in_two.count, 2);
    EXPECT_EQ(in_two.first_layer, "direct");
    EXPECT_EQ(in_two.first_x, 3);
    EXPECT_EQ(in_two.first_y, 2);
    beauty.at(2, 2).r = -std::numeric_limits<float>::infinity();
    direct.at(0, 0).r = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(replace_non_finite(beauty, aovs).first_layer, "beauty");
}

// Blender's RenderResult.load_from_file fills a pass only from channels named
// <view layer>.<pass>.<channel>, and Combined needs its A: the names the add-on reads.
TEST(FrameLayers, BlenderNamesAreViewLayerPassAndChannelWithCombinedAlpha) {
    Image beauty(2, 2), alpha(2, 2);
    beauty.at(1, 0) = {0.25f, 0.5f, 0.75f};
    alpha.at(1, 0) = {1, 1, 1};
    std::vector<NamedImage> aovs{{"direct", Image(2, 2)}, {"influence", GreyImage(2, 2)}};
    std::get<GreyImage>(aovs[1].image).at(0, 1) = 3;
    const std::string path = (std::filesystem::temp_directory_path() / "steadylight_blender_names.exr").string();
    write_exr(path, blender_exr_layers("View Layer.001", beauty, aovs, alpha), ExrPixelType::float32);
    std::vector<std::string> names;
    for (const ExrChannelInfo& channel : read_exr_channels(path)) names.push_back(channel.name);
    EXPECT_EQ(names, (std::vector<std::string>{"View Layer.001.Combined.A", "View Layer.001.Combined.B",
                                               "View Layer.001.Combined.G", "View Layer.001.Combined.R",
                                               "View Layer.001.direct.B", "View Layer.001.direct.G",
                                               "View Layer.001.direct.R", "View Layer.001.influence.X"}));
    EXPECT_EQ(read_exr_channel(path, "View Layer.001.Combined.G")[1], 0.5f);
    EXPECT_EQ(read_exr_channel(path, "View Layer.001.Combined.A")[1], 1);
    EXPECT_EQ(read_exr_channel(path, "View Layer.001.influence.X")[2], 3);
    std::filesystem::remove(path);
}

}  // namespace
}  // namespace steadylight
