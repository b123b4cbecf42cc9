// World images (world_image.h, with exr_reading.h and radiance_hdr.h): EXR and Radiance HDR files
// read back as written, and each kind of bad file refused with a message naming the file and
// what is wrong.
#include "steadylight/scene/world_image.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfTiledOutputFile.h>
#include <gtest/gtest.h>
#include <stb_image_write.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "steadylight/scene/exr_reading.h"
#include "steadylight/scene/radiance_hdr.h"
#include "support/input_error.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;
using testing::input_error_of;

std::string test_folder() {
    const fs::path folder = fs::path(STEADYLIGHT_BINARY_DIR) / "world_image_test";
    fs::create_directories(folder);
    return folder.string();
}

/// A width x height image whose pixels all differ: (x, y) is (x + 1, y + 1, x * y) / 4.
Image ramp(int width, int height) {
    Image image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) image.at(x, y) = Rgb{x + 1.0f, y + 1.0f, float(x * y)} * 0.25f;
    return image;
}

struct ExrOptions {
    Imf::Compression compression = Imf::ZIP_COMPRESSION;
    Imf::PixelType type = Imf::FLOAT;
    bool alpha = false;
    Imath::V2i origin{0, 0};  // where the data window starts
    int tile = 0;             // the side of square tiles; 0 for scanlines
};

/// `image` as an EXR with channels R, G, B (and A = 0.5), through OpenEXR directly.
void write_test_exr(const std::string& path, const Image& image, const ExrOptions& options = {}) {
    const Imath::Box2i window(options.origin, options.origin + Imath::V2i(image.width - 1, image.height - 1));
    Imf::Header header(window, window);
    header.compression() = options.compression;
    std::vector<std::vector<float>> floats(4);
    std::vector<std::vector<half>> halves(4);
    for (const Rgb& p : image.pixels)
        for (size_t c = 0; c < 4; ++c) {
            floats[c].push_back(c < 3 ? p[int(c)] : 0.5f);
            halves[c].push_back(half(floats[c].back()));
        }
    Imf::FrameBuffer buffer;
    const char* names[] = {"R", "G", "B", "A"};
    for (size_t c = 0; c < (options.alpha ? 4u : 3u); ++c) {
        header.channels().insert(names[c], Imf::Channel(options.type));
        const void* data = options.type == Imf::HALF ? static_cast<void*>(halves[c].data()) : floats[c].data();
        buffer.insert(names[c], Imf::Slice::Make(options.type, data, window));
    }
    if (options.tile > 0) {
        header.setTileDescription(Imf::TileDescription(unsigned(options.tile), unsigned(options.tile)));
        Imf::TiledOutputFile out(path.c_str(), header);
        out.setFrameBuffer(buffer);
        out.writeTiles(0, out.numXTiles() - 1, 0, out.numYTiles() - 1);
        return;
    }
    Imf::OutputFile out(path.c_str(), header);
    out.setFrameBuffer(buffer);
    out.writePixels(image.height);
}

std::string write_bytes(const std::string& name, const std::string& bytes) {
    const std::string path = test_folder() + "/" + name;
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    return path;
}

std::string exr_file(const std::string& name, const Image& image, const ExrOptions& options = {}) {
    const std::string path = test_folder() + "/" + name;
    write_test_exr(path, image, options);
    return path;
}

std::string read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A Radiance HDR file's header for width x height in the standard orientation.
std::string hdr_header(int width, int height) {
    return "#?RADIANCE\n# a comment\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=1.0\n\n-Y " + std::to_string(height) + " +X " +
           std::to_string(width) + "\n";
}

TEST(WorldImage, ExrReadsBackAsWrittenInEveryLayout) {
    const Image image = ramp(8, 4);
    EXPECT_EQ(load_world_image(exr_file("float.exr", image)).pixels, image.pixels);
    EXPECT_EQ(load_world_image(exr_file("rgba.exr", image, {.alpha = true})).pixels, image.pixels);
    EXPECT_EQ(load_world_image(exr_file("uncompressed.exr", image, {.compression = Imf::NO_COMPRESSION})).pixels,
              image.pixels);
    // Quarters and small integers are exact in half too.
    EXPECT_EQ(load_world_image(exr_file("half.exr", image, {.type = Imf::HALF})).pixels, image.pixels);
    // A data window that does not start at (0, 0), and rows in more than one block of reading.
    const Image tall = ramp(200, 100);
    EXPECT_EQ(load_world_image(exr_file("offset.exr", tall, {.origin = {-7, 30}})).pixels, tall.pixels);
    // Tiles, larger than the image too.
    EXPECT_EQ(load_world_image(exr_file("tiled.exr", tall, {.tile = 32})).pixels, tall.pixels);
    EXPECT_EQ(load_world_image(exr_file("one_tile.exr", image, {.tile = 64})).pixels, image.pixels);
}

// DWAB, the lossy compression of Blender's world images, keeps a smooth image within about 1%.
TEST(WorldImage, DwabCompressedExrReadsBackCloseToWhatWasWritten) {
    Image image(64, 32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) image.at(x, y) = Rgb{1 + 0.5f * std::sin(x * 0.1f), 2 + 0.01f * float(y), 0.7f};
    const Image back = load_world_image(exr_file("dwab.exr", image, {.compression = Imf::DWAB_COMPRESSION}));
    ASSERT_EQ(back.pixels.size(), image.pixels.size());
    for (size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(back.pixels[i][c], image.pixels[i][c], 0.02f * image.pixels[i][c]);
}

// A pixel (r, g, b, e) stands for ((r, g, b) + 0.5) 2^(e - 136): here e = 129 gives (r + 0.5) / 128.
TEST(WorldImage, RadianceHdrPixelsAreTheMiddlesOfTheirIntervals) {
    std::string flat = hdr_header(4, 2);
    for (int i = 0; i < 8; ++i) flat += i == 5 ? std::string(4, '\0') : std::string("\x80\x40\x20\x81", 4);
    const Image image = load_world_image(write_bytes("flat.hdr", flat));
    ASSERT_EQ(image.width, 4);
    ASSERT_EQ(image.height, 2);
    EXPECT_EQ(image.at(0, 0), (Rgb{128.5f, 64.5f, 32.5f} / 128));
    EXPECT_EQ(image.at(1, 1), Rgb{});  // exponent 0: black
}

// Run-length encoded scanlines, as stb_image_write (another program) writes them, read back
// within the precision of 8-bit mantissas under the exponent of a pixel's largest component.
TEST(WorldImage, RunLengthEncodedHdrReadsBackWithinItsPrecision) {
    Image image(64, 32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) image.at(x, y) = Rgb{x < 40 ? 1.0f : 3.0f, 0.01f * float(y + 1), 100.0f + x};
    std::string bytes;
    const auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
    };
    ASSERT_TRUE(stbi_write_hdr_to_func(append, &bytes, 64, 32, 3, &image.pixels[0].r));
    const Image back = load_world_image(write_bytes("rle.hdr", bytes));
    ASSERT_EQ(back.pixels.size(), image.pixels.size());
    for (size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(back.pixels[i][c], image.pixels[i][c], max_component(image.pixels[i]) / 128) << i;
}

TEST(WorldImage, MissingFilesFoldersFifosAndDevicesAreRefusedByName) {
    EXPECT_EQ(input_error_of([] { load_world_image("/nowhere/sky.exr"); }),
              "/nowhere/sky.exr: cannot open: file not found");
    EXPECT_NE(input_error_of([] { load_world_image(test_folder()); }).find("not a regular file: it is a folder"),
              std::string::npos);
    EXPECT_NE(
        input_error_of([] { load_world_image("/dev/zero"); }).find("/dev/zero: not a regular file: it is a device"),
        std::string::npos);
    const std::string fifo = test_folder() + "/sky.fifo";
    fs::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_NE(input_error_of([&] { load_world_image(fifo); }).find("not a regular file: it is a FIFO"),
              std::string::npos);
}

TEST(WorldImage, OtherFilesAreRefusedAsNotAWorldImage) {
    const std::string path = write_bytes("sky.png", "\x89PNG\r\n\x1a\n");
    EXPECT_EQ(input_error_of([&] { load_world_image(path); }),
              path + ": not an EXR or Radiance HDR image, which a world image must be");
}

// A header cut short, attributes whose stated size runs past the end of the file (OpenEXR's C++
// reader would allocate that size first), tiles far larger than the image, and pixel data cut
// short.
TEST(WorldImage, DamagedExrFilesAreRefused) {
    EXPECT_EQ(input_error_of([] { decode_world_image(std::string("\x76\x2f\x31\x01\x02\0\0\0garbage", 15), "a.exr"); }),
              "a.exr: cannot read EXR: End of file attempting to read header");
    const std::string whole = read_bytes(exr_file("whole.exr", ramp(16, 8)));
    std::string oversized = whole;
    const size_t size_at = oversized.find(std::string("channels\0chlist\0", 16)) + 16;
    oversized.replace(size_at, 4, "\xff\xff\xff\x7f");
    EXPECT_EQ(input_error_of([&] { decode_world_image(oversized, "b.exr"); }),
              "b.exr: cannot read EXR: Attribute 'channels', type 'chlist': Invalid size 2147483647");
    // An attribute of a type OpenEXR does not know, stated as 2 GB.
    const std::string unknown =
        whole.substr(0, 8) + std::string("junk\0mytype\0\xff\xff\xff\x7f", 16) + whole.substr(8);
    EXPECT_NE(input_error_of([&] { decode_world_image(unknown, "c.exr"); }).find("c.exr: cannot read EXR: "),
              std::string::npos);
    // Tiles 262144 x 1024 for an image of 16 x 8 (the C++ reader allocates a tile for each thread).
    std::string huge_tiles = read_bytes(exr_file("tiles.exr", ramp(16, 8), {.tile = 4}));
    huge_tiles.replace(huge_tiles.find(std::string("tiles\0tiledesc\0", 15)) + 19, 8,
                       std::string("\0\0\x04\0\0\x04\0\0", 8));
    EXPECT_EQ(input_error_of([&] { decode_world_image(huge_tiles, "e.exr"); }),
              "e.exr: a damaged EXR image (tiles of 262144 x 1024 pixels in an image of 16 x 8)");
    EXPECT_NE(input_error_of([&] {
                  decode_world_image(whole.substr(0, whole.size() - 20), "d.exr");
              }).find("d.exr: cannot read EXR"),
              std::string::npos);
}

TEST(WorldImage, AnImageThatIsNotTwiceAsWideAsHighIsRefused) {
    const std::string path = exr_file("square.exr", ramp(6, 6));
    EXPECT_EQ(input_error_of([&] { load_world_image(path); }),
              path + ": the world image is 6 x 6 texels, but an equirectangular image is twice as wide as it is high");
    EXPECT_NE(input_error_of([&] {
                  load_world_image(write_bytes("tall.hdr", hdr_header(4, 4)));
              }).find("is 4 x 4 texels, but an equirectangular image"),
              std::string::npos);
}

// The size is checked from the header: a file that only claims to be large is refused as large.
TEST(WorldImage, AnImageBeyondTheTextureLimitsIsRefusedFromItsHeader) {
    const std::string path = write_bytes("huge.hdr", hdr_header(16386, 8193));
    EXPECT_EQ(input_error_of([&] { load_world_image(path); }),
              path +
                  ": the world image is too large (16386 x 8193 texels; at most 16384 on a side and 8192 x 8192 "
                  "in all)");
    EXPECT_NE(input_error_of([&] {
                  load_world_image(write_bytes("wide.hdr", hdr_header(16000, 8000)));
              }).find("too large (16000 x 8000 texels"),
              std::string::npos);
    // An EXR whose data window says 16 million pixels wide, with 8 x 4 pixels of data.
    std::string exr = read_bytes(exr_file("small.exr", ramp(8, 4)));
    const size_t window_at = exr.find(std::string("dataWindow\0box2i\0", 17)) + 17 + 4;
    exr.replace(window_at + 8, 4, std::string("\xff\xff\xff\x00", 4));  // xMax = 2^24 - 1
    EXPECT_EQ(input_error_of([&] { decode_world_image(exr, "wide.exr"); }),
              "wide.exr: the world image is too large (16777216 x 4 texels; at most 16384 on a side and 8192 x 8192 in "
              "all)");
}

TEST(WorldImage, NanAndInfinitePixelsAreRefusedNamingTheFirst) {
    Image image = ramp(8, 4);
    image.at(5, 2).g = std::numeric_limits<float>::quiet_NaN();
    image.at(1, 3).b = std::numeric_limits<float>::infinity();
    const std::string path = exr_file("nan.exr", image);
    EXPECT_EQ(input_error_of([&] { load_world_image(path); }),
              path +
                  ": pixel (5, 2) of the world image is (1.5, nan, 2.5): radiance must be finite, and 2 of its 32 "
                  "pixels are not");
}

// Lossy compression leaves values slightly below zero in good images: those read as 0. A value
// far below zero (here -1 in an image of mean about 1.5) is an error.
TEST(WorldImage, SlightlyNegativeValuesReadAsZeroAndClearlyNegativeOnesAreRefused) {
    Image image = ramp(8, 4);
    image.at(2, 1).r = -0.01f;
    const Image read = load_world_image(exr_file("noise.exr", image));
    EXPECT_EQ(read.at(2, 1), (Rgb{0, 0.5f, 0.5f}));
    EXPECT_EQ(read.at(3, 1), image.at(3, 1));
    image.at(6, 0).b = -1;
    image.at(7, 3).g = -2;
    const std::string path = exr_file("negative.exr", image);
    const std::string message = input_error_of([&] { load_world_image(path); });
    EXPECT_NE(
        message.find(path + ": pixel (6, 0) of the world image is (1.75, 0.25, -1): radiance must not be negative"),
        std::string::npos)
        << message;
    EXPECT_NE(message.find("2 of its 32 pixels are not"), std::string::npos) << message;
}

// The run-length data ends inside a scanline (a file that made stb_image loop forever), a run of
// length zero, and a header promising more rows than the file holds.
TEST(WorldImage, DamagedHdrFilesAreRefusedAtOnce) {
    const std::string row = std::string("\x02\x02\x00\x08", 4) + std::string("\x88\x05\x88\x05\x88\x05\x88\x81", 8);
    const std::string cut = hdr_header(8, 4) + row + row + row + row.substr(0, 10) + "\x08\x01\x02";
    EXPECT_NE(input_error_of([&] {
                  decode_world_image(cut, "cut.hdr");
              }).find("cut.hdr: a damaged Radiance HDR image (row 3: the file ends inside it)"),
              std::string::npos);
    const std::string zero_run = hdr_header(8, 4) + std::string("\x02\x02\x00\x08\x00", 5) + std::string(200, '\x01');
    EXPECT_NE(input_error_of([&] { decode_world_image(zero_run, "zero.hdr"); }).find("row 0: a run of length zero"),
              std::string::npos);
    const std::string short_file = hdr_header(1024, 512) + std::string(100, '\x01');
    EXPECT_NE(input_error_of([&] {
                  decode_world_image(short_file, "short.hdr");
              }).find("100 bytes of pixels cannot hold 1024 x 512"),
              std::string::npos);
}

TEST(WorldImage, HdrLayoutsOtherThanRgbFromTheTopAreRefused) {
    EXPECT_NE(input_error_of([] {
                  decode_world_image("#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 2\n", "x.hdr");
              }).find("x.hdr: not a Radiance HDR image (FORMAT=32-bit_rle_xyze: only 32-bit_rle_rgbe"),
              std::string::npos);
    EXPECT_NE(input_error_of([] {
                  decode_world_image("#?RADIANCE\n\n+Y 1 +X 2\n", "up.hdr");
              }).find("its resolution line \"+Y 1 +X 2\" is not \"-Y height +X width\""),
              std::string::npos);
    EXPECT_NE(input_error_of([] {
                  decode_world_image("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n", "open.hdr");
              }).find("its header has no end"),
              std::string::npos);
}

// Blender's own world images (Debian's blender-data; skipped without it): DWAB-compressed EXRs
// of 1024 x 512 with a few slightly negative values.
TEST(WorldImage, BlendersWorldImagesLoad) {
    const fs::path folder = "/usr/share/blender/datafiles/studiolights/world";
    if (!fs::is_directory(folder)) GTEST_SKIP() << folder << " is missing (Debian package blender-data)";
    for (const char* name : {"forest.exr", "sunset.exr", "studio.exr"}) {
        const Image image = load_world_image((folder / name).string());
        EXPECT_EQ(image.width, 1024);
        EXPECT_EQ(image.height, 512);
        double sum = 0;
        for (const Rgb& p : image.pixels) {
            ASSERT_TRUE(is_finite(p) && p.r >= 0 && p.g >= 0 && p.b >= 0);
            sum += luminance(p);
        }
        EXPECT_GT(sum / double(image.pixels.size()), 0.1) << name;
    }
}

}  // namespace
}  // namespace steadylight
