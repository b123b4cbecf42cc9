#include "steadylight/output/image_writer.h"

#include <Imath/half.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <utility>

#include "steadylight/base/error.h"
#include "steadylight/base/rng.h"
#include "steadylight/output/frame_layers.h"
#include "steadylight/output/frame_names.h"
#include "steadylight/scene/image_decoding.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

Image gradient(int width, int height) {
    Image image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) image.at(x, y) = {float(x) / 4, float(y) * 3, 0.25f};
    return image;
}

TEST(ImageWriter, FrameNamesHaveFourDigits) {
    EXPECT_EQ(frame_file_name("out/ball", "ball", 7, "exr"), "out/ball/ball_0007.exr");
}

TEST(ImageWriter, ExrRoundTripKeepsHalfPrecision) {
    const std::string path = (fs::temp_directory_path() / "steadylight_roundtrip.exr").string();
    const Image image = gradient(7, 5);
    write_exr(path, image);
    const Image back = read_exr(path);
    ASSERT_EQ(back.width, 7);
    ASSERT_EQ(back.height, 5);
    for (size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(back.pixels[i][c], image.pixels[i][c], 1e-3f * (1 + image.pixels[i][c]));
    EXPECT_FALSE(fs::exists(path + ".partial"));
    fs::remove(path);
}

TEST(ImageWriter, TruncatedExrIsAnInputError) {
    const std::string path = (fs::temp_directory_path() / "steadylight_truncated.exr").string();
    write_exr(path, gradient(64, 64));
    fs::resize_file(path, fs::file_size(path) / 2);
    EXPECT_THROW(read_exr(path), InputError);
    fs::remove(path);
}

TEST(ImageWriter, PngIsWrittenWhole) {
    const std::string path = (fs::temp_directory_path() / "steadylight_frame.png").string();
    write_png(path, gradient(8, 8));
    EXPECT_GT(fs::file_size(path), 8u);
    EXPECT_FALSE(fs::exists(path + ".partial"));
    fs::remove(path);
}

TEST(ImageWriter, WritingIntoAMissingFolderFailsCleanly) {
    EXPECT_THROW(write_png("/nonexistent/folder/x.png", gradient(2, 2)), std::runtime_error);
}

std::vector<std::string> channel_names(const std::vector<ExrChannelInfo>& channels) {
    std::vector<std::string> names;
    for (const ExrChannelInfo& channel : channels) names.push_back(channel.name);
    return names;
}

TEST(ImageWriter, FrameExrHasBeautyAsDefaultAndNamedLayerAndScalarAovsAsY) {
    const std::string path = (fs::temp_directory_path() / "steadylight_layers.exr").string();
    // Lines of ten: the halves are made eight at a time and then one by one.
    const Image beauty = gradient(10, 4);
    GreyImage influence(10, 4);
    for (size_t i = 0; i < influence.pixels.size(); ++i) influence.pixels[i] = float(i);
    const std::vector<NamedImage> aovs = {{"direct", gradient(10, 4)}, {"influence", influence}};
    write_exr(path, frame_exr_layers(beauty, aovs));

    // OpenEXR lists channels sorted by name.
    const std::vector<ExrChannelInfo> channels = read_exr_channels(path);
    EXPECT_EQ(channel_names(channels), (std::vector<std::string>{"B", "G", "R", "beauty.B", "beauty.G", "beauty.R",
                                                                 "direct.B", "direct.G", "direct.R", "influence.Y"}));
    for (const ExrChannelInfo& channel : channels) EXPECT_EQ(channel.type, ExrPixelType::half) << channel.name;
    const Image named = read_exr(path, "beauty"), plain = read_exr(path);
    EXPECT_EQ(named.pixels, plain.pixels);
    const std::vector<float> back = read_exr_channel(path, "influence.Y");
    ASSERT_EQ(back.size(), influence.pixels.size());
    for (size_t i = 0; i < back.size(); ++i) EXPECT_EQ(back[i], float(i)) << i;
    EXPECT_EQ(read_exr(path, "influence").at(9, 3), (Rgb{39, 39, 39}));

    // The same channels grouped into layers, in header order.
    const std::vector<ExrLayerInfo> layers = read_exr_layers(path);
    ASSERT_EQ(layers.size(), 4u);
    EXPECT_EQ(layers[0].name, "");
    EXPECT_EQ(layers[0].channels, (std::vector<std::string>{"B", "G", "R"}));
    EXPECT_EQ(layers[1].name, "beauty");
    EXPECT_EQ(layers[3].name, "influence");
    EXPECT_EQ(layers[3].channels, (std::vector<std::string>{"Y"}));
    fs::remove(path);
}

// With a transparent background both beauty layers carry A (what Nuke reads as rgba.alpha and
// Blender as the layer's alpha); the AOVs stay as they are. Without alpha nothing changes.
TEST(ImageWriter, FrameExrWithAlphaHasAnAChannelInBothBeautyLayers) {
    const std::string path = (fs::temp_directory_path() / "steadylight_alpha.exr").string();
    const Image beauty = gradient(6, 4);
    Image alpha(6, 4);
    for (size_t i = 0; i < alpha.pixels.size(); ++i) alpha.pixels[i] = Rgb{1, 1, 1} * (float(i % 5) / 4);
    GreyImage grey(6, 4);
    for (size_t i = 0; i < grey.pixels.size(); ++i) grey.pixels[i] = alpha.pixels[i].r;
    const std::vector<NamedImage> aovs = {{"direct", gradient(6, 4)}, {"influence", grey}};
    write_exr(path, frame_exr_layers(beauty, aovs, &alpha));
    EXPECT_EQ(channel_names(read_exr_channels(path)),
              (std::vector<std::string>{"A", "B", "G", "R", "beauty.A", "beauty.B", "beauty.G", "beauty.R", "direct.B",
                                        "direct.G", "direct.R", "influence.Y"}));
    for (const std::string channel : {"A", "beauty.A"}) {
        const std::vector<float> values = read_exr_channel(path, channel);
        ASSERT_EQ(values.size(), alpha.pixels.size());
        for (size_t i = 0; i < values.size(); ++i) EXPECT_EQ(values[i], alpha.pixels[i].r) << channel << " " << i;
    }
    EXPECT_EQ(read_exr(path).pixels, read_exr(path, "beauty").pixels);
    EXPECT_THROW(read_exr_channel(path, "direct.A"), InputError);

    write_exr(path, frame_exr_layers(beauty, aovs));
    for (const ExrChannelInfo& channel : read_exr_channels(path)) EXPECT_FALSE(channel.name.ends_with("A"));
    fs::remove(path);
}

/// The colour type of a PNG file's bytes (its IHDR's): 2 RGB, 6 RGBA.
int png_colour_type(const std::vector<unsigned char>& png) { return png.at(25); }

TEST(ImageWriter, PngWithAlphaIsRgbaAndWithoutRgb) {
    const Image image = gradient(5, 3);
    Image alpha(5, 3);
    alpha.at(1, 1) = {1, 1, 1};
    EXPECT_EQ(png_colour_type(encode_png(image)), 2);
    const std::vector<unsigned char> png = encode_png(image, {}, &alpha);
    EXPECT_EQ(png_colour_type(png), 6);
    const DecodedImage decoded = decode_image(png.data(), png.size());
    ASSERT_EQ(decoded.width, 5);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x) EXPECT_EQ(decoded.rgba[size_t(y * 5 + x) * 4 + 3], x == 1 && y == 1 ? 255 : 0);
}

// The PNG's pixels are the view transform's bytes, every one: decoded by another decoder
// (stb_image), RGB and RGBA, of sizes from one pixel up, with values all over the byte range
// (the filtered bytes wrap around) and values from a few levels (the Paeth predictor's ties).
TEST(ImageWriter, PngDecodesToTheEncodedBytes) {
    Pcg32 rng(5);
    const std::pair<int, int> sizes[] = {{1, 1}, {7, 5}, {61, 37}};
    for (const auto& [width, height] : sizes) {
        Image image(width, height), alpha(width, height);
        const auto level = [&] { return float(rng.next_u32() % 3) / 2; };
        for (size_t i = 0; i < image.pixels.size(); ++i)
            image.pixels[i] = i % 2 ? Rgb{level(), level(), level()}
                                    : Rgb{rng.next_float(), rng.next_float() * 0.1f, rng.next_float() * 2};
        for (Rgb& pixel : alpha.pixels) pixel = Rgb{1, 1, 1} * (rng.next_float() < 0.5f ? 1.0f : rng.next_float());
        const Image* const alphas[] = {nullptr, &alpha};
        for (const Image* a : alphas) {
            const std::vector<unsigned char> expected = encode_srgb8(image, {}, a);
            const std::vector<unsigned char> png = encode_png(image, {}, a);
            const DecodedImage decoded = decode_image(png.data(), png.size());
            ASSERT_EQ(decoded.width, width);
            ASSERT_EQ(decoded.height, height);
            const size_t components = a ? 4 : 3;
            for (size_t i = 0; i < size_t(width * height); ++i)
                for (size_t c = 0; c < 4; ++c)
                    ASSERT_EQ(decoded.rgba[i * 4 + c], c < components ? expected[i * components + c] : 255)
                        << width << "x" << height << " pixel " << i << " channel " << c;
        }
    }
}

// Half layers hold only finite values: beyond 65504 a half is +inf (a compositor's blur would
// spread it), so larger values are clamped to it, and a NaN is written as 0.
// In the first eight pixels of a line (converted eight at a time where the processor can) and in
// the last ones (one by one) alike.
TEST(ImageWriter, HalfExrValuesAreFinite) {
    const std::string path = (fs::temp_directory_path() / "steadylight_finite.exr").string();
    Image image(11, 1);
    for (const int x : {0, 9}) {
        image.at(x, 0) = {1e6f, -1e6f, 2};
        image.at(x + 1, 0) = {std::numeric_limits<float>::quiet_NaN(), 1, std::numeric_limits<float>::infinity()};
    }
    image.at(2, 0) = {-0.0f, -std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::quiet_NaN()};
    write_exr(path, image);
    const Image back = read_exr(path);
    for (const int x : {0, 9}) {
        EXPECT_EQ(back.at(x, 0), (Rgb{65504, -65504, 2})) << x;
        EXPECT_EQ(back.at(x + 1, 0), (Rgb{0, 1, 65504})) << x;
    }
    EXPECT_EQ(back.at(2, 0), (Rgb{0, -65504, 0}));
    EXPECT_TRUE(std::signbit(back.at(2, 0).r));   // -0 stays -0
    EXPECT_FALSE(std::signbit(back.at(2, 0).b));  // a NaN becomes +0, whatever its sign
    fs::remove(path);
}

// A half channel whose values all fit is written from the image's floats by OpenEXR, one whose
// values do not is clamped first: either way each value is the half nearest to it, as half()
// rounds (to even), the tiny ones to denormals and zero too.
TEST(ImageWriter, HalfExrValuesAreTheNearestHalves) {
    const std::string path = (fs::temp_directory_path() / "steadylight_nearest.exr").string();
    Image image(61, 150);  // lines in three batches of the writer's, the last not a multiple of 8 values
    Pcg32 rng(11);
    for (Rgb& pixel : image.pixels) {
        const auto value = [&] { return (rng.next_float() - 0.5f) * std::exp2(float(int(rng.next_u32() % 56) - 40)); };
        pixel = {value(), value(), value()};
    }
    image.at(0, 0).b = 1e6f;  // the blue channel is clamped, the others are written as they are
    write_exr(path, image);
    const Image back = read_exr(path);
    for (size_t i = 1; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) ASSERT_EQ(back.pixels[i][c], float(half(image.pixels[i][c]))) << i << " " << c;
    EXPECT_EQ(back.at(0, 0).b, 65504);
    fs::remove(path);
}

TEST(ImageWriter, PngFileHoldsTheEncodedBytes) {
    const std::string path = (fs::temp_directory_path() / "steadylight_encoded.png").string();
    const ViewTransform view{.exposure_ev = 1, .curve = ViewCurve::filmic};
    write_png(path, gradient(5, 3), view);
    std::ifstream in(path, std::ios::binary);
    const std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    EXPECT_EQ(bytes, encode_png(gradient(5, 3), view));
    EXPECT_NE(bytes, encode_png(gradient(5, 3)));
    fs::remove(path);
}

TEST(ImageWriter, FloatExrKeepsFullPrecision) {
    const std::string path = (fs::temp_directory_path() / "steadylight_float.exr").string();
    Image image(3, 2);
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = Rgb{1.0001f, 1e-7f, 70000.0f} * float(i + 1);
    write_exr(path, {{"", &image}, {"L_y", &image}}, ExrPixelType::float32);
    for (const ExrChannelInfo& channel : read_exr_channels(path))
        EXPECT_EQ(channel.type, ExrPixelType::float32) << channel.name;
    EXPECT_EQ(read_exr(path, "L_y").pixels, image.pixels);  // 70000 overflows half; 1.0001 rounds in it
    fs::remove(path);
}

TEST(ImageWriter, ExrPixelTypeNames) {
    EXPECT_EQ(parse_exr_pixel_type("half"), ExrPixelType::half);
    EXPECT_EQ(parse_exr_pixel_type("float"), ExrPixelType::float32);
    EXPECT_THROW(parse_exr_pixel_type("uint"), InputError);
}

TEST(ImageWriter, SrgbCurveIsContinuousAndClamped) {
    EXPECT_NEAR(linear_to_srgb(0.0031308f), 12.92f * 0.0031308f, 1e-5f);
    EXPECT_NEAR(linear_to_srgb(0.0031309f), 12.92f * 0.0031308f, 1e-4f);
    EXPECT_NEAR(linear_to_srgb(7.0f), 1.0f, 1e-6f);
    EXPECT_EQ(linear_to_srgb(-1.0f), 0.0f);
    EXPECT_NEAR(linear_to_srgb(0.5f), 0.7354f, 1e-3f);
}

}  // namespace
}  // namespace steadylight
