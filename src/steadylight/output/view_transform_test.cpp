// Tests for the PNG view transform (view_transform.h): exposure, the sRGB curve at the
// standard's known points, the filmic curve's shape, deterministic 8-bit encoding, and straight
// alpha.
#include "steadylight/output/view_transform.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

#include "steadylight/base/error.h"

namespace steadylight {
namespace {

TEST(ViewTransform, ExposurePlusOneDoublesLinearValues) {
    EXPECT_FLOAT_EQ(apply_exposure(0.3f, 1), 0.6f);
    EXPECT_FLOAT_EQ(apply_exposure(0.3f, 0), 0.3f);
    EXPECT_FLOAT_EQ(apply_exposure(0.3f, -2), 0.075f);
}

TEST(ViewTransform, ExposurePlusOneMatchesDoublingTheImage) {
    Image image(4, 1), doubled(4, 1);
    for (int x = 0; x < 4; ++x) {
        image.at(x, 0) = Rgb{0.05f, 0.1f, 0.2f} * float(x);
        doubled.at(x, 0) = image.at(x, 0) * 2.0f;
    }
    EXPECT_EQ(encode_srgb8(image, {.exposure_ev = 1, .dither = false}), encode_srgb8(doubled, {.dither = false}));
}

TEST(ViewTransform, SrgbMatchesThePiecewiseFormulaOfIec61966) {
    // Linear segment below 0.0031308, 1.055 v^(1/2.4) - 0.055 above.
    EXPECT_FLOAT_EQ(linear_to_srgb(0), 0);
    EXPECT_NEAR(linear_to_srgb(0.002f), 12.92f * 0.002f, 1e-7f);
    EXPECT_NEAR(linear_to_srgb(0.0031308f), 0.040449936f, 1e-6f);
    EXPECT_NEAR(linear_to_srgb(0.18f), 0.46135613f, 1e-5f);  // mid grey
    EXPECT_NEAR(linear_to_srgb(0.5f), 0.73535698f, 1e-5f);
    EXPECT_FLOAT_EQ(linear_to_srgb(1), 1);
}

TEST(ViewTransform, SrgbIsClampedAndIgnoresNan) {
    EXPECT_EQ(linear_to_srgb(-1), 0);
    EXPECT_FLOAT_EQ(linear_to_srgb(7), 1);  // 1.055f - 0.055f is 1 within a float ulp
    EXPECT_EQ(linear_to_srgb(std::nanf("")), 0);
}

TEST(ViewTransform, FilmicMapsZeroToZeroAndSaturatesAtOne) {
    EXPECT_FLOAT_EQ(filmic_curve(0), 0);
    EXPECT_FLOAT_EQ(filmic_curve(-3), 0);
    EXPECT_LE(filmic_curve(5.6f), 1.0f);
    EXPECT_NEAR(filmic_curve(5.6f), 1.0f, 1e-5f);  // the white point 11.2 after the bias of 2
    EXPECT_EQ(filmic_curve(1e3f), 1);
    EXPECT_EQ(filmic_curve(INFINITY), 1);
    EXPECT_EQ(filmic_curve(std::nanf("")), 0);
}

TEST(ViewTransform, FilmicIsMonotonicAndCompressesHighlights) {
    float previous = 0;
    for (float v = 0.001f; v < 20; v *= 1.05f) {
        const float f = filmic_curve(v);
        EXPECT_GE(f, previous) << "at " << v;
        EXPECT_LE(f, 1.0f);
        previous = f;
    }
    // Values the standard transform clips still differ under filmic.
    EXPECT_LT(filmic_curve(1.5f), filmic_curve(3.0f));
    EXPECT_LT(filmic_curve(3.0f), 1.0f);
}

TEST(ViewTransform, StandardCurveClamps) {
    EXPECT_EQ(apply_view_curve(2, ViewCurve::standard), 1);
    EXPECT_EQ(apply_view_curve(-1, ViewCurve::standard), 0);
    EXPECT_EQ(apply_view_curve(0.25f, ViewCurve::standard), 0.25f);
}

TEST(ViewTransform, DitherIsDeterministicAndMovesAtMostHalfACodeValue) {
    Image image(16, 16);
    for (Rgb& pixel : image.pixels) pixel = {0.2f, 0.21f, 0.22f};
    const auto plain = encode_srgb8(image, {.dither = false});
    const auto dithered = encode_srgb8(image, {});
    EXPECT_EQ(dithered, encode_srgb8(image, {}));
    bool differs = false;
    for (size_t i = 0; i < plain.size(); ++i) {
        const double exact = 255.0 * linear_to_srgb(image.pixels[i / 3][int(i % 3)]);
        EXPECT_LE(std::abs(dithered[i] - exact), 1.0) << i;
        differs |= dithered[i] != plain[i];
    }
    EXPECT_TRUE(differs);
}

// PNG alpha is straight: a pixel half covered by a surface holds half the surface's light
// (premultiplied) and is written with the surface's own colour, through the same curves, and
// alpha 128; where alpha is 0 nothing is left. Dither moves the colours only.
TEST(ViewTransform, AlphaDividesThePremultipliedColourBeforeTheCurves) {
    const Rgb surface{0.9f, 0.35f, 0.02f};
    Image straight(3, 1), premultiplied(3, 1), alpha(3, 1);
    const float coverage[] = {1, 0.5f, 0};
    for (int x = 0; x < 3; ++x) {
        straight.at(x, 0) = surface;
        premultiplied.at(x, 0) = surface * coverage[x];
        alpha.at(x, 0) = Rgb{1, 1, 1} * coverage[x];
    }
    for (const ViewTransform view : {ViewTransform{.dither = false}, ViewTransform{.exposure_ev = 1.5f},
                                     ViewTransform{.curve = ViewCurve::filmic}}) {
        const std::vector<unsigned char> rgb = encode_srgb8(straight, view);
        const std::vector<unsigned char> rgba = encode_srgb8(premultiplied, view, &alpha);
        ASSERT_EQ(rgba.size(), 3u * 4);
        for (int c = 0; c < 3; ++c) {
            EXPECT_EQ(rgba[size_t(c)], rgb[size_t(c)]) << c;
            EXPECT_EQ(rgba[size_t(4 + c)], rgb[size_t(3 + c)]) << c;
            EXPECT_EQ(rgba[size_t(8 + c)], 0) << c;
        }
        EXPECT_EQ(rgba[3], 255);
        EXPECT_EQ(rgba[7], 128);
        EXPECT_EQ(rgba[11], 0);
    }
}

TEST(ViewTransform, BytesAreTheCurvesRoundedToTheNearestCode) {
    // Without dither a byte is the code value rounded half away from zero (std::lround), clamped:
    // values across the whole range, through both curves, at several exposures.
    Image image(257, 3);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const float v = std::ldexp(float(x + 1) / 64.0f, y * 3 - 6) - (x % 17 == 0 ? 0.25f : 0.0f);
            image.at(x, y) = {v, v * 1.0001f, x == 5 ? std::nanf("") : v * 0.999f};
        }
    for (const ViewCurve curve : {ViewCurve::standard, ViewCurve::filmic})
        for (const float ev : {0.0f, 1.5f, -2.25f}) {
            const std::vector<unsigned char> bytes = encode_srgb8(image, {ev, curve, false});
            for (size_t i = 0; i < image.pixels.size(); ++i)
                for (int c = 0; c < 3; ++c) {
                    const float code =
                        255 * linear_to_srgb(apply_view_curve(apply_exposure(image.pixels[i][c], ev), curve));
                    ASSERT_EQ(bytes[3 * i + size_t(c)], std::clamp(std::lround(code), 0L, 255L)) << i << " " << c;
                }
        }
}

TEST(ViewTransform, UnknownNameIsAnInputError) {
    EXPECT_EQ(parse_view_curve("filmic"), ViewCurve::filmic);
    EXPECT_THROW(parse_view_curve("agx"), InputError);
}

TEST(ViewTransform, SrgbCurveIsTheFormulaWithinFloatRounding) {
    // Every 16th float of the curve's power segment, against the formula in double: the
    // tabulated curve keeps to a few float steps of the true value (a code value is 1/255).
    double worst = 0;
    for (uint32_t bits = std::bit_cast<uint32_t>(0.0031309f); bits <= std::bit_cast<uint32_t>(1.0f); bits += 16) {
        const float v = std::bit_cast<float>(bits);
        worst = std::max(worst, std::abs(double(linear_to_srgb(v)) - (1.055 * std::pow(double(v), 1 / 2.4) - 0.055)));
    }
    EXPECT_LT(worst, 1e-7);
    EXPECT_EQ(linear_to_srgb(1), 1);
}

}  // namespace
}  // namespace steadylight
