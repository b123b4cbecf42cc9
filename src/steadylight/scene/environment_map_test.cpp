// The world's light (environment_map.h): white furnaces, the image mapped as Blender's
// Environment Texture maps it, samples that follow their pdf and find a bright pixel as often as
// its share of the light, and a hash that sees every input.
#include "steadylight/scene/environment_map.h"

#include <gtest/gtest.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <cmath>
#include <tuple>
#include <vector>

#include "steadylight/base/rng.h"
#include "steadylight/base/sampling.h"
#include "support/chi_square.h"

namespace steadylight {
namespace {

using testing::Chi2;
using testing::chi2_bound;
using testing::chi2_test;

/// An image of one colour.
Image constant_image(int width, int height, Rgb value) {
    Image image(width, height);
    std::fill(image.pixels.begin(), image.pixels.end(), value);
    return image;
}

/// An image whose pixel (x, y) holds (x, y, 1): radiance(w) says which pixel w looks up.
Image index_image(int width, int height) {
    Image image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) image.at(x, y) = {float(x), float(y), 1};
    return image;
}

/// A smooth sky: brighter towards the top and towards one side, never black.
Image smooth_image(int width, int height) {
    Image image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float u = (x + 0.5f) / width, v = 1 - (y + 0.5f) / height;
            image.at(x, y) = Rgb{0.2f, 0.3f, 0.5f} * (1 + 3 * v * v) * (1.5f + std::cos(2 * pi * u));
        }
    return image;
}

/// The pixel (column, row) that direction w falls in on a width x height image without
/// rotation, straight from the mapping: u = atan2(z, x) / 2π + ½, v = asin(y) / π + ½, and
/// row (1 - v) height.
std::pair<int, int> pixel_of(Vec3 w, int width, int height) {
    const double u = std::atan2(double(w.z), double(w.x)) / (2 * std::acos(-1.0)) + 0.5;
    const double v = std::asin(std::clamp(double(w.y), -1.0, 1.0)) / std::acos(-1.0) + 0.5;
    return {std::min(int(u * width), width - 1), std::min(int((1 - v) * height), height - 1)};
}

/// ∫ L cos θ dω over the hemisphere around +y, estimated from the map's own samples.
double irradiance_at_the_ground(const EnvironmentMap& map, int n) {
    Pcg32 rng(5);
    double sum = 0;
    for (int i = 0; i < n; ++i)
        if (const auto s = map.sample(rng.next_vec2()); s && s->w.y > 0)
            sum += luminance(s->radiance) * s->w.y / s->pdf;
    return sum / n;
}

// A white furnace: under uniform radiance L, a horizontal surface receives π L, whether L is a
// colour, an image of one value, or one turned and scaled by a strength.
TEST(EnvironmentMap, WhiteFurnaceGivesPiLFromItsOwnSamples) {
    const int n = 1'000'000;
    EXPECT_NEAR(irradiance_at_the_ground(EnvironmentMap(Rgb{0.5f, 0.5f, 0.5f}), n), pi * 0.5, 0.01 * pi * 0.5);
    const EnvironmentMap image(constant_image(64, 32, {0.5f, 0.5f, 0.5f}), 1, 0);
    EXPECT_NEAR(irradiance_at_the_ground(image, n), pi * 0.5, 0.01 * pi * 0.5);
    const EnvironmentMap turned(constant_image(64, 32, {0.25f, 0.25f, 0.25f}), 2, 37);
    EXPECT_NEAR(irradiance_at_the_ground(turned, n), pi * 0.5, 0.01 * pi * 0.5);
}

TEST(EnvironmentMap, MeanLuminanceIsTheRadianceAveragedOverTheSphere) {
    EXPECT_FLOAT_EQ(EnvironmentMap(Rgb{1, 0, 0}).mean_luminance(), 0.2126f);
    EXPECT_NEAR(EnvironmentMap(constant_image(64, 32, {1, 1, 1}), 3, 10).mean_luminance(), 3.0f, 1e-5f);
    // The top half lit: half the sphere.
    Image top = constant_image(64, 32, {});
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 64; ++x) top.at(x, y) = {1, 1, 1};
    EXPECT_NEAR(EnvironmentMap(top, 1, 0).mean_luminance(), 0.5f, 1e-5f);
}

/// The direction through the centre of pixel (x, y) of a width x height image, without rotation.
Vec3 pixel_centre(int x, int y, int width, int height) {
    const float phi = 2 * pi * ((x + 0.5f) / width - 0.5f), theta = pi * (y + 0.5f) / height;
    return {std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
}

/// w turned about +y by `degrees` as the rotation of the mapping turns it.
Vec3 turned(Vec3 w, float degrees) {
    const float a = degrees * pi / 180;
    return {w.x * std::cos(a) + w.z * std::sin(a), w.y, -w.x * std::sin(a) + w.z * std::cos(a)};
}

/// A 64 x 32 black image with 2 x 2 blocks where the mapping says +x (red), +z (green) and -z
/// (blue) look, centred on the pixel corners there, and the top and bottom rows lit.
Image compass_image() {
    Image image = constant_image(64, 32, {});
    const auto block = [&](int column, Rgb colour) {
        for (int x = column - 1; x <= column; ++x)
            for (int y = 15; y <= 16; ++y) image.at(x, y) = colour;
    };
    block(32, {1, 0, 0});  // u = 1/2
    block(48, {0, 1, 0});  // u = 3/4
    block(16, {0, 0, 1});  // u = 1/4
    for (int x = 0; x < 64; ++x) {
        image.at(x, 0) = {5, 5, 5};
        image.at(x, 31) = {7, 7, 7};
    }
    return image;
}

// The centre column looks down +x, u = 3/4 down +z, u = 1/4 down -z; the top row is +y and the
// bottom row -y.
TEST(EnvironmentMap, TheImageIsMappedAsBlendersEnvironmentTexture) {
    const EnvironmentMap compass(compass_image(), 1, 0);
    EXPECT_EQ(compass.radiance({1, 0, 0}), (Rgb{1, 0, 0}));
    EXPECT_EQ(compass.radiance({0, 0, 1}), (Rgb{0, 1, 0}));
    EXPECT_EQ(compass.radiance({0, 0, -1}), (Rgb{0, 0, 1}));
    EXPECT_EQ(compass.radiance({-1, 0, 0}), Rgb{});
    EXPECT_EQ(compass.radiance({0, 1, 0}), (Rgb{5, 5, 5}));
    EXPECT_EQ(compass.radiance({0, -1, 0}), (Rgb{7, 7, 7}));
    // Against the mapping written out, in many directions and at every pixel's centre.
    const EnvironmentMap map(index_image(64, 32), 1, 0);
    Pcg32 rng(9);
    for (int i = 0; i < 1000; ++i) {
        const Vec3 w = sample_uniform_sphere(rng.next_vec2());
        const auto [x, y] = pixel_of(w, 64, 32);
        EXPECT_EQ(map.radiance(w), (Rgb{float(x), float(y), 1})) << to_string(w);
    }
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) ASSERT_EQ(map.radiance(pixel_centre(x, y, 64, 32)), (Rgb{float(x), float(y), 1}));
}

// A rotation a turns the look-up direction about +y (x' = x cos a + z sin a, z' = -x sin a +
// z cos a), so the picture turns by -a: at 90 degrees +x looks up what -z did and +z what +x
// did. The strength scales the radiance.
TEST(EnvironmentMap, RotationTurnsTheLookUpAboutYAndStrengthScales) {
    const EnvironmentMap quarter(compass_image(), 2, 90);
    EXPECT_EQ(quarter.radiance({1, 0, 0}), (Rgb{0, 0, 2}));
    EXPECT_EQ(quarter.radiance({0, 0, 1}), (Rgb{2, 0, 0}));
    EXPECT_EQ(quarter.radiance({0, 1, 0}), (Rgb{10, 10, 10}));
    EXPECT_EQ(EnvironmentMap(compass_image(), 1, -90).radiance({1, 0, 0}), (Rgb{0, 1, 0}));
    const EnvironmentMap map(index_image(64, 32), 1, 37);
    Pcg32 rng(10);
    for (int i = 0; i < 1000; ++i) {
        const Vec3 w = sample_uniform_sphere(rng.next_vec2());
        const auto [x, y] = pixel_of(turned(w, 37), 64, 32);
        EXPECT_EQ(map.radiance(w), (Rgb{float(x), float(y), 1})) << to_string(w);
    }
}

// One bright pixel in a dim sky: samples land in its patch of directions as often as its share
// of luminance times solid angle says, and there radiance / pdf is what it is everywhere else
// (the estimator of the sky's light has almost no variance).
TEST(EnvironmentMap, SamplesFindABrightPixelInProportionToItsLight) {
    const int width = 256, height = 128, bright_x = 40, bright_y = 30;
    Image image = constant_image(width, height, {0.1f, 0.1f, 0.1f});
    image.at(bright_x, bright_y) = {5000, 4000, 3000};
    const EnvironmentMap map(image, 1, 0);
    // The pixel's share: its luminance times its solid angle over the integral over the sphere.
    const double theta0 = pi * bright_y / height, theta1 = pi * (bright_y + 1) / height;
    const double solid_angle = 2 * pi / width * (std::cos(theta0) - std::cos(theta1));
    const double expected = luminance(image.at(bright_x, bright_y)) * solid_angle / (4 * pi * map.mean_luminance());
    ASSERT_GT(expected, 0.2);
    Pcg32 rng(3);
    const int n = 200'000;
    int inside = 0;
    for (int i = 0; i < n; ++i) {
        const auto s = map.sample(rng.next_vec2());
        ASSERT_TRUE(s);
        inside += pixel_of(s->w, width, height) == std::pair(bright_x, bright_y);
    }
    const double sigma = std::sqrt(expected * (1 - expected) / n);
    EXPECT_NEAR(double(inside) / n, expected, 5 * sigma + 0.002 * expected);
    // radiance / pdf is 4π times the mean luminance (within the floor's share) at the bright
    // pixel's centre and wherever sin θ changes little across a pixel.
    const float estimate = 4 * pi * map.mean_luminance();
    const Vec3 centre = pixel_centre(bright_x, bright_y, width, height);
    EXPECT_NEAR(luminance(map.radiance(centre)) / map.pdf(centre), estimate, 0.005 * estimate);
    for (int i = 0; i < 20'000; ++i) {
        const Vec3 w = sample_uniform_sphere(rng.next_vec2());
        if (std::abs(w.y) > 0.5f) continue;
        EXPECT_NEAR(luminance(map.radiance(w)) / map.pdf(w), estimate, 0.015 * estimate) << to_string(w);
    }
}

TEST(EnvironmentMap, SamplesFollowTheirPdf) {
    for (const EnvironmentMap& map : {EnvironmentMap(smooth_image(128, 64), 1, 0),
                                      EnvironmentMap(smooth_image(128, 64), 0.5f, 123), EnvironmentMap(Rgb{1, 2, 3})}) {
        const Chi2 chi2 = chi2_test(
            [&](Pcg32& rng) -> std::optional<Vec3> {
                const auto s = map.sample(rng.next_vec2());
                return s ? std::optional(s->w) : std::nullopt;
            },
            [&](Vec3 w) { return map.pdf(w); }, -1, 8, 16, 200'000);
        ASSERT_GT(chi2.dof, 100);
        EXPECT_LT(chi2.statistic, chi2_bound(chi2.dof)) << "dof " << chi2.dof;
    }
}

// pdf(sample.w) and radiance(sample.w) are the sample's, bit for bit; the pdf integrates to one
// over the sphere (estimated with uniform directions).
TEST(EnvironmentMap, PdfAgreesWithSamplesAndIntegratesToOne) {
    Image image = smooth_image(64, 32);
    image.at(10, 3) = {0, 0, 0};
    image.at(50, 20) = {20, 20, 20};
    for (const EnvironmentMap& map : {EnvironmentMap(image, 1, 0), EnvironmentMap(image, 2, -71)}) {
        Pcg32 rng(8);
        for (int i = 0; i < 100'000; ++i) {
            const auto s = map.sample(rng.next_vec2());
            ASSERT_TRUE(s);
            ASSERT_EQ(map.pdf(s->w), s->pdf);
            ASSERT_EQ(map.radiance(s->w), s->radiance);
            ASSERT_NEAR(length(s->w), 1.0f, 1e-5f);
        }
        const int n = 1'000'000;
        double sum = 0;
        for (int i = 0; i < n; ++i) sum += map.pdf(sample_uniform_sphere(rng.next_vec2())) / uniform_sphere_pdf();
        EXPECT_NEAR(sum / n, 1.0, 0.01);
    }
}

// Sampling for a surface's normal: samples agree with pdf_facing bit for bit, it integrates to
// one over the sphere, and the samples fall in each pixel as often as it says (a chi-square test
// over the pixels, whose probabilities the pdf at their centres gives exactly: it is constant over
// a pixel in (u, v)); for normals on and between the fixed ones, turned images, a bright and a
// black pixel, and an odd size (cells cut at the image's edge). Rarely a sample fails: rounding
// puts it across the edge of a cell that sends nothing towards the normal. A uniform colour has
// none.
TEST(EnvironmentMap, FacingSamplesFollowTheirPdf) {
    constexpr int width = 72, height = 36;
    Image image = smooth_image(width, height);
    image.at(50, 20) = {20, 20, 20};
    image.at(10, 3) = {};
    const Vec3 normals[] = {{0, 1, 0}, normalize(Vec3{0.3f, -0.5f, 0.8f}), normalize(Vec3{-1, 0.05f, 0.02f})};
    for (const float rotation : {0.0f, -71.0f})
        for (const Vec3 n : normals) {
            const EnvironmentMap map(image, 1, rotation);
            Pcg32 rng(8);
            const int n_samples = 400'000;
            std::vector<double> observed(size_t(width * height), 0.0);
            int failed = 0;
            for (int i = 0; i < n_samples; ++i) {
                const auto s = map.sample_facing(n, rng.next_vec2());
                if (!s) {
                    ++failed;
                    continue;
                }
                ASSERT_EQ(map.pdf_facing(n, s->w), s->pdf);
                ASSERT_EQ(map.radiance(s->w), s->radiance);
                const auto [x, y] = pixel_of(s->w, width, height);
                observed[size_t(y * width + x)] += 1;
            }
            EXPECT_LT(failed, n_samples / 10'000);
            double sum = 0;
            for (int i = 0; i < 1'000'000; ++i)
                sum += map.pdf_facing(n, sample_uniform_sphere(rng.next_vec2())) / uniform_sphere_pdf();
            EXPECT_NEAR(sum / 1'000'000, 1.0, 0.01) << to_string(n);
            if (rotation != 0) continue;  // pixel_of maps without rotation
            double statistic = 0, pooled_expected = 0, pooled_observed = 0;
            int bins = 0;
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) {
                    const float theta = pi * (float(y) + 0.5f) / height,
                                phi = 2 * pi * ((float(x) + 0.5f) / width - 0.5f);
                    const Vec3 centre{std::sin(theta) * std::cos(phi), std::cos(theta),
                                      std::sin(theta) * std::sin(phi)};
                    const double expected = double(map.pdf_facing(n, centre)) * 2 * pi * pi * std::sin(theta) /
                                            (width * height) * n_samples;
                    const double o = observed[size_t(y * width + x)];
                    if (expected < 5) {
                        pooled_expected += expected, pooled_observed += o;
                        continue;
                    }
                    statistic += (o - expected) * (o - expected) / expected;
                    ++bins;
                }
            if (pooled_expected > 0) {
                statistic +=
                    (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
                ++bins;
            }
            ASSERT_GT(bins, 500);
            EXPECT_LT(statistic, chi2_bound(bins - 1)) << "bins " << bins << " " << to_string(n);
        }
    EXPECT_FALSE(EnvironmentMap(Rgb{1, 1, 1}).sample_facing({0, 1, 0}, {0.5f, 0.5f}));
    EXPECT_EQ(EnvironmentMap(Rgb{1, 1, 1}).pdf_facing({0, 1, 0}, {0, 1, 0}), 0.0f);
}

// What the facing sampling is for: under a sky over a bright ground, a floor's samples by the
// map alone go mostly below it, where they bring nothing; facing the floor, few do, and the
// irradiance they estimate is the same with a fraction of the variance.
TEST(EnvironmentMap, FacingSamplesGoWhereTheSurfaceSeesLight) {
    Image image(64, 32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) image.at(x, y) = y < 16 ? Rgb{0.2f, 0.3f, 0.6f} : Rgb{1, 0.9f, 0.8f};
    const EnvironmentMap map(image, 1, 0);
    const Vec3 up{0, 1, 0};
    const auto estimate = [&](bool facing) {
        Pcg32 rng(3);
        const int n = 200'000;
        double sum = 0, sum2 = 0;
        int below = 0;
        for (int i = 0; i < n; ++i) {
            const auto s = facing ? map.sample_facing(up, rng.next_vec2()) : map.sample(rng.next_vec2());
            if (!s) continue;
            below += s->w.y <= 0;
            const double value = luminance(s->radiance) * std::max(0.0f, s->w.y) / s->pdf;
            sum += value, sum2 += value * value;
        }
        const double mean = sum / n;
        return std::tuple{mean, sum2 / n - mean * mean, double(below) / n};
    };
    const auto [by_map, map_variance, map_below] = estimate(false);
    const auto [facing, facing_variance, facing_below] = estimate(true);
    const double exact = pi * luminance({0.2f, 0.3f, 0.6f});
    EXPECT_NEAR(by_map, exact, 0.01 * exact);
    EXPECT_NEAR(facing, exact, 0.01 * exact);
    EXPECT_GT(map_below, 0.7);
    EXPECT_LT(facing_below, 0.01);
    EXPECT_LT(facing_variance, 0.1 * map_variance);
}

// Sampling follows the picture, not its units: an image scaled down to the smallest floats or up
// towards the largest gives the same pdf.
TEST(EnvironmentMap, PdfDoesNotDependOnTheImagesScale) {
    // Scenes load on the main thread, with denormals as the C++ default keeps them; a test that
    // ran a parallel loop before, in the same process, left the render threads' flush-to-zero on.
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_OFF);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_OFF);
    Image image = smooth_image(64, 32);
    image.at(5, 5) = {};
    const EnvironmentMap reference(image, 1, 0);
    for (const float scale : {1e-40f, 1e30f}) {
        Image scaled = image;
        for (Rgb& p : scaled.pixels) p *= scale;
        const EnvironmentMap map(scaled, 1, 0);
        Pcg32 rng(12);
        for (int i = 0; i < 1000; ++i) {
            const Vec3 w = sample_uniform_sphere(rng.next_vec2());
            ASSERT_NEAR(map.pdf(w), reference.pdf(w), 1e-4f * reference.pdf(w)) << scale << " " << to_string(w);
        }
    }
}

// A black pixel still has pdf > 0 (the floor), so that every direction with light in it can be
// sampled; a map black everywhere gives no samples and pdf 0.
TEST(EnvironmentMap, BlackPixelsKeepAPdfAndABlackMapHasNone) {
    Image image = constant_image(64, 32, {1, 1, 1});
    image.at(20, 10) = {0, 0, 0};
    image.at(21, 10) = {0, 0, 1e-44f};  // luminance underflows to 0
    const EnvironmentMap map(image, 1, 0);
    const Vec3 black = pixel_centre(20, 10, 64, 32);
    ASSERT_EQ(map.radiance(black), Rgb{});
    EXPECT_GT(map.pdf(black), 0.0f);
    EXPECT_LT(map.pdf(black), 0.01f * map.pdf({1, 0, 0}));
    for (const EnvironmentMap& none :
         {EnvironmentMap(Rgb{}), EnvironmentMap(constant_image(8, 4, {}), 1, 0), EnvironmentMap(image, 0, 0)}) {
        EXPECT_FALSE(none.sample({0.3f, 0.6f}));
        EXPECT_EQ(none.pdf({0, 1, 0}), 0.0f);
        EXPECT_EQ(none.mean_luminance(), 0.0f);
    }
}

TEST(EnvironmentMap, HashChangesWithEveryInput) {
    const Image image = smooth_image(16, 8);
    const uint64_t base = EnvironmentMap(image, 1, 0).hash();
    EXPECT_EQ(EnvironmentMap(image, 1, 0).hash(), base);
    Image changed = image;
    changed.at(7, 3).g += 0.01f;
    EXPECT_NE(EnvironmentMap(changed, 1, 0).hash(), base);
    EXPECT_NE(EnvironmentMap(image, 1.5f, 0).hash(), base);
    EXPECT_NE(EnvironmentMap(image, 1, 10).hash(), base);
    // The same pixels laid out 8 x 16 instead of 16 x 8.
    Image transposed = image;
    std::swap(transposed.width, transposed.height);
    EXPECT_NE(EnvironmentMap(transposed, 1, 0).hash(), base);
    EXPECT_NE(EnvironmentMap(Rgb{1, 1, 1}).hash(), EnvironmentMap(Rgb{1, 1, 0.5f}).hash());
    EXPECT_EQ(EnvironmentMap(Rgb{1, 1, 1}).hash(), EnvironmentMap(Rgb{1, 1, 1}).hash());
}

}  // namespace
}  // namespace steadylight
