// The truth suite's figures on images whose answer is known.
#include "steadylight/quality/image_error.h"

#include <gtest/gtest.h>

#include "support/scene_builder.h"

namespace steadylight {
namespace {

Image flat(int w, int h, float value) {
    Image image(w, h);
    for (Rgb& p : image.pixels) p = Rgb{1, 1, 1} * value;
    return image;
}

TEST(ImageError, IdenticalImagesHaveNoError) {
    const Image a = flat(8, 8, 0.5f);
    const ImageError e = image_error(a, a);
    EXPECT_EQ(e.pixel_rmse, 0);
    EXPECT_EQ(e.block_rmse, 0);
    EXPECT_EQ(e.mean_ratio, 1);
    EXPECT_EQ(e.pixels, 64);
}

TEST(ImageError, ABrighterImageShowsInEveryFigure) {
    const ImageError e = image_error(flat(8, 8, 0.55f), flat(8, 8, 0.5f));
    EXPECT_NEAR(e.pixel_rmse, 0.1, 1e-6);
    EXPECT_NEAR(e.block_rmse, 0.1, 1e-6);
    EXPECT_NEAR(e.mean_ratio, 1.1, 1e-6);
}

TEST(ImageError, BlocksForgivePixelNoiseThatAveragesOut) {
    Image noisy = flat(8, 8, 0.5f);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) noisy.at(x, y) = Rgb{1, 1, 1} * ((x + y) % 2 ? 0.6f : 0.4f);
    const ImageError e = image_error(noisy, flat(8, 8, 0.5f));
    EXPECT_NEAR(e.pixel_rmse, 0.2, 1e-6);
    EXPECT_NEAR(e.block_rmse, 0.0, 1e-6);
}

TEST(ImageError, MaskedPixelsAreLeftOutAndLuminanceIsNotClamped) {
    Image image = flat(4, 4, 0.5f), reference = flat(4, 4, 0.5f);
    image.at(1, 1) = {100, 100, 100};  // an emitter seen differently
    PixelMask mask(16, 0);
    mask[1 * 4 + 1] = 1;
    EXPECT_EQ(image_error(image, reference, mask).pixel_rmse, 0);
    EXPECT_EQ(image_error(image, reference, mask).pixels, 15);
    EXPECT_GT(image_error(image, reference).pixel_rmse, 10);  // unclamped: 99.5 over a mean of 0.5
}

TEST(EmitterMask, CoversTheLightAndItsBorder) {
    // A camera looking straight at an emitting quad that fills the middle of the image.
    SceneDesc desc = testing::make_empty_scene({0, 0, -2}, {0, 0, 0}, 16, 16, 40);
    const int black = testing::add_material(desc, {.reflectance = {0, 0, 0}});
    testing::add_object(desc, make_quad({-0.2f, -0.2f, 0}, {0, 0.4f, 0}, {0.4f, 0, 0}), black, {1, 1, 1});
    const Scene scene(std::move(desc));
    const PreparedFrame frame(scene, 0);
    const PixelMask mask = emitter_mask(frame.context());
    EXPECT_EQ(mask[8 * 16 + 8], 1);  // the centre sees the light
    EXPECT_EQ(mask[0], 0);           // a corner does not
    long masked = 0;
    for (const uint8_t m : mask) masked += m;
    EXPECT_GT(masked, 4);
    EXPECT_LT(masked, 16 * 16 / 2);
}

TEST(TemporalNoise, ZeroWhenTheMethodChangesAsTheReferenceDoes) {
    const Image a = flat(4, 4, 0.5f), b = flat(4, 4, 0.52f);
    const TemporalNoise noise = temporal_noise({{a, b}}, {{a, b}});
    EXPECT_EQ(noise.all, 0);
    EXPECT_EQ(noise.all_pixels, 16);
    EXPECT_EQ(noise.far_pixels, 0);  // the reference changes by 4% everywhere
}

TEST(TemporalNoise, ChangeWhereTheLightIsStillIsNoiseAndCountsAsFar) {
    const Image still = flat(4, 4, 0.5f);
    Image flickering = still;
    flickering.at(0, 0) = Rgb{1, 1, 1} * 0.58f;  // +0.08 on one pixel of 16
    const TemporalNoise noise = temporal_noise({{still, flickering}}, {{still, still}});
    EXPECT_NEAR(noise.all, 0.08 / 16 / 0.5, 1e-6);
    EXPECT_NEAR(noise.far, noise.all, 1e-9);
    EXPECT_EQ(noise.far_pixels, 16);
    EXPECT_NEAR(noise.far_signed, noise.far, 1e-9);  // it brightened
    EXPECT_NEAR(noise.far_own, noise.far, 1e-9);     // the reference did not change
    EXPECT_NEAR(temporal_noise({{flickering, still}}, {{still, still}}).far_signed, -noise.far, 1e-9);
}

TEST(TemporalNoise, LargeTrueChangesAreLeftOut) {
    const Image dark = flat(4, 4, 0.1f), bright = flat(4, 4, 0.5f);  // a shadow's coverage edge
    EXPECT_EQ(temporal_noise({{dark, dark}}, {{dark, bright}}).all_pixels, 0);
}

}  // namespace
}  // namespace steadylight
