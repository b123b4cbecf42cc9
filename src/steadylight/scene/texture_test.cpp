// Texture sampling (texture.h) on tiny images with known answers: wrap modes, filters, sRGB,
// KHR_texture_transform. shading/textured_surface_test.cpp follows textures to surfaces.
#include "steadylight/scene/texture.h"

#include <gtest/gtest.h>

namespace steadylight {
namespace {

/// A width x 1 image whose red channel is `values`, the others 0, alpha 255.
TextureImage row_image(const std::vector<uint8_t>& values) {
    TextureImage image{.name = "row", .width = int(values.size()), .height = 1};
    for (const uint8_t v : values) image.rgba.insert(image.rgba.end(), {v, 0, 0, 255});
    return image;
}

float red(const TextureImage& image, const TextureRef& ref, float u, bool srgb = false) {
    return sample_texture(image, ref, {u, 0.5f}, srgb)[0];
}

TEST(Texture, NearestPicksTheTexelUnderTheCoordinate) {
    const TextureImage image = row_image({0, 51, 102, 153});
    const TextureRef ref{.image = 0, .filter = TextureFilter::nearest};
    EXPECT_FLOAT_EQ(red(image, ref, 0.3f), 51 / 255.0f);
    EXPECT_FLOAT_EQ(red(image, ref, 0.99f), 153 / 255.0f);
}

TEST(Texture, WrapModesPlaceCoordinatesOutsideZeroOne) {
    const TextureImage image = row_image({0, 51, 102, 153});
    TextureRef ref{.image = 0, .filter = TextureFilter::nearest};
    // u = 1.1 is texel 4.4: repeat -> texel 0, clamp -> texel 3, mirrored -> texel 3.
    ref.wrap_s = TextureWrap::repeat;
    EXPECT_FLOAT_EQ(red(image, ref, 1.1f), 0);
    EXPECT_FLOAT_EQ(red(image, ref, -0.1f), 153 / 255.0f);  // texel -0.4 -> 3
    ref.wrap_s = TextureWrap::clamp_to_edge;
    EXPECT_FLOAT_EQ(red(image, ref, 1.1f), 153 / 255.0f);
    EXPECT_FLOAT_EQ(red(image, ref, -3.0f), 0);
    ref.wrap_s = TextureWrap::mirrored_repeat;
    EXPECT_FLOAT_EQ(red(image, ref, 1.1f), 153 / 255.0f);  // texel 4 mirrors to 3
    EXPECT_FLOAT_EQ(red(image, ref, 1.3f), 102 / 255.0f);  // texel 5 mirrors to 2
    EXPECT_FLOAT_EQ(red(image, ref, -0.1f), 0);            // texel -1 mirrors to 0
}

TEST(Texture, BilinearInterpolatesBetweenTexelCentres) {
    const TextureImage image = row_image({0, 200, 100, 100});
    const TextureRef ref{.image = 0, .wrap_s = TextureWrap::clamp_to_edge};
    // Centres of texels 0 and 1 sit at u = 0.125 and 0.375; a quarter of the way is u = 0.1875.
    EXPECT_NEAR(red(image, ref, 0.125f), 0, 1e-6f);
    EXPECT_NEAR(red(image, ref, 0.1875f), 50 / 255.0f, 1e-6f);
    EXPECT_NEAR(red(image, ref, 0.25f), 100 / 255.0f, 1e-6f);
    // Repeat wraps the filter too: halfway between texel 3 and texel 0.
    const TextureRef repeat{.image = 0};
    EXPECT_NEAR(red(image, repeat, 1.0f), 50 / 255.0f, 1e-6f);
}

TEST(Texture, SrgbIsDecodedBeforeFiltering) {
    EXPECT_NEAR(srgb_to_linear(255), 1.0f, 1e-6f);
    EXPECT_NEAR(srgb_to_linear(128), 0.21586f, 1e-5f);
    EXPECT_NEAR(srgb_to_linear(10), 10 / 255.0f / 12.92f, 1e-7f);
    const TextureImage image = row_image({0, 255});
    const TextureRef ref{.image = 0, .wrap_s = TextureWrap::clamp_to_edge};
    // Halfway between black and white is linear 0.5 (code value 188), not sRGB 128.
    EXPECT_NEAR(red(image, ref, 0.5f, true), 0.5f, 1e-6f);
    const Rgba alpha = sample_texture(image, ref, {0.5f, 0.5f}, true);
    EXPECT_FLOAT_EQ(alpha[3], 1.0f);  // alpha stays linear
}

TEST(Texture, TransformScalesRotatesThenOffsets) {
    // KHR_texture_transform's example: rotation pi/2 maps (1, 0) to (0, -1).
    const TextureRef rotated{.rotation = pi / 2};
    const Vec2 r = rotated.transform({1, 0});
    EXPECT_NEAR(r.x, 0, 1e-6f);
    EXPECT_NEAR(r.y, -1, 1e-6f);
    const TextureRef all{.offset = {0.5f, 0.25f}, .rotation = pi / 2, .scale = {2, 3}};
    const Vec2 t = all.transform({1, 1});  // scale (2, 3), rotate -> (3, -2), offset -> (3.5, -1.75)
    EXPECT_NEAR(t.x, 3.5f, 1e-5f);
    EXPECT_NEAR(t.y, -1.75f, 1e-5f);
}

}  // namespace
}  // namespace steadylight
