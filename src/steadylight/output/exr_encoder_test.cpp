#include "steadylight/output/exr_encoder.h"

#include <Imath/half.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "steadylight/base/rng.h"
#include "steadylight/output/image_writer.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

/// A channel's values as encode_exr takes them (every third float), and its name.
struct TestChannel {
    std::string name;
    std::vector<float> values;  // 3 floats a pixel, the first one the channel's
};

std::vector<ExrChannelValues> values_of(const std::vector<TestChannel>& channels) {
    std::vector<ExrChannelValues> out;
    for (const TestChannel& channel : channels) out.push_back({channel.name, channel.values.data()});
    return out;
}

/// Channels of `width` x `height` pixels: a smooth ramp (which deflates well), a constant, noise
/// (the bits of halves at random, which do not deflate: their blocks are stored as they are), and
/// one with a name too long for OpenEXR's short names; listed out of name order.
std::vector<TestChannel> test_channels(int width, int height) {
    const size_t pixels = size_t(width) * size_t(height);
    std::vector<TestChannel> channels = {{"ramp.R", {}}, {"A", {}}, {"noise.G", {}}, {std::string(40, 'l') + ".B", {}}};
    Pcg32 rng(7);
    for (TestChannel& channel : channels) channel.values.assign(3 * pixels, -1.0f);
    for (size_t i = 0; i < pixels; ++i) {
        channels[0].values[3 * i] = float(i % size_t(width)) * 0.01f + float(i / size_t(width));
        channels[1].values[3 * i] = 0.5f;
        // Any finite half, its bits at random, or a float beyond the halves (clamped).
        half noise;
        do noise.setBits(uint16_t(rng.next_u32()));
        while (!noise.isFinite());
        channels[2].values[3 * i] = i % 97 == 0 ? 1e6f : float(noise);
        channels[3].values[3 * i] = rng.next_float() < 0.5f ? 0.0f : 3.0f;
    }
    return channels;
}

std::string temp_file(const std::string& name) { return (fs::temp_directory_path() / name).string(); }

void write_bytes(const std::string& path, const std::vector<unsigned char>& bytes) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

/// The same channels written by OpenEXR's own writer (ZIP), as the reference.
void write_with_openexr(const std::string& path, int width, int height, const std::vector<TestChannel>& channels,
                        ExrPixelType type) {
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    const Imf::PixelType pixel_type = type == ExrPixelType::half ? Imf::HALF : Imf::FLOAT;
    // OpenEXR writes the values of its pixel type as they are: give it the halves encode_exr
    // makes (clamped), or the floats.
    const size_t value_bytes = type == ExrPixelType::half ? sizeof(half) : sizeof(float);
    std::vector<std::vector<char>> planes;
    for (const TestChannel& channel : channels) {
        header.channels().insert(channel.name, Imf::Channel(pixel_type));
        std::vector<char> plane(channel.values.size() / 3 * value_bytes);
        for (size_t i = 0; i < channel.values.size() / 3; ++i) {
            const float value = channel.values[3 * i];
            const half as_half(std::clamp(value, -65504.0f, 65504.0f));
            std::memcpy(
                plane.data() + i * value_bytes,
                type == ExrPixelType::half ? static_cast<const void*>(&as_half) : static_cast<const void*>(&value),
                value_bytes);
        }
        planes.push_back(std::move(plane));
    }
    Imf::OutputFile out(path.c_str(), header);
    Imf::FrameBuffer buffer;
    for (size_t c = 0; c < channels.size(); ++c)
        buffer.insert(channels[c].name,
                      Imf::Slice(pixel_type, planes[c].data(), value_bytes, value_bytes * size_t(width)));
    out.setFrameBuffer(buffer);
    out.writePixels(height);
}

TEST(ExrEncoder, OpenExrReadsWhatOpenExrWrote) {
    // 37 lines: two whole blocks of 16 and a short one.
    const int width = 53, height = 37;
    const std::vector<TestChannel> channels = test_channels(width, height);
    for (const ExrPixelType type : {ExrPixelType::half, ExrPixelType::float32}) {
        const std::string ours = temp_file("steadylight_encoder_ours.exr");
        const std::string theirs = temp_file("steadylight_encoder_theirs.exr");
        write_bytes(ours, encode_exr(width, height, values_of(channels), type));
        write_with_openexr(theirs, width, height, channels, type);
        const std::vector<ExrChannelInfo> listed = read_exr_channels(ours);
        ASSERT_EQ(listed.size(), channels.size());
        for (size_t c = 0; c < listed.size(); ++c) {
            EXPECT_EQ(listed[c].name, read_exr_channels(theirs)[c].name);  // sorted by name
            EXPECT_EQ(listed[c].type, type);
            const std::vector<float> a = read_exr_channel(ours, listed[c].name);
            const std::vector<float> b = read_exr_channel(theirs, listed[c].name);
            ASSERT_EQ(a.size(), size_t(width) * size_t(height));
            EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << listed[c].name;
        }
        fs::remove(ours), fs::remove(theirs);
    }
}

TEST(ExrEncoder, BlocksThatDoNotDeflateAreStoredAsTheyAre) {
    // Noise alone: every block is stored as it is, and the file is its values and a little more.
    const int width = 64, height = 32;
    std::vector<TestChannel> channels = test_channels(width, height);
    channels = {channels[2]};
    const std::vector<unsigned char> bytes = encode_exr(width, height, values_of(channels), ExrPixelType::half);
    const size_t values = size_t(width) * size_t(height) * 2;
    EXPECT_GE(bytes.size(), values);
    EXPECT_LT(bytes.size(), values + 400);
    const std::string path = temp_file("steadylight_encoder_noise.exr");
    write_bytes(path, bytes);
    const std::vector<float> back = read_exr_channel(path, "noise.G");
    for (size_t i = 0; i < back.size(); ++i)
        ASSERT_EQ(back[i], float(half(std::clamp(channels[0].values[3 * i], -65504.0f, 65504.0f)))) << i;
    fs::remove(path);
    // A ramp deflates to a small part of its values.
    channels = {test_channels(width, height)[0]};
    EXPECT_LT(encode_exr(width, height, values_of(channels), ExrPixelType::half).size(), values / 2);
}

}  // namespace
}  // namespace steadylight
