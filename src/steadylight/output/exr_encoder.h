// Encoding frames as OpenEXR files: single-part scanline files (OpenEXR 2), ZIP-compressed, as
// OpenEXR's own writer lays them out: blocks of 16 lines, each line's channels in name order, the
// bytes split into their even and odd halves and delta-coded, then deflated (or stored as they
// are where deflating does not shorten them). Our own encoder rather than OpenEXR's OutputFile,
// so that the blocks are deflated by igzip (output/deflate.h) at a fifth of zlib's cost; OpenEXR
// still reads every file (the tests read them with it).
#pragma once

#include <string>
#include <vector>

namespace steadylight {

/// How EXR channels are stored: 16-bit half (the default; enough for display-referred work
/// and a third of the size) or 32-bit float.
enum class ExrPixelType { half, float32 };

/// A channel to encode: its name and its values, row by row from the top, the value of pixel i
/// being `values[stride i]` (3: one component of an image's Rgb; 1: a grey image's values).
struct ExrChannelValues {
    std::string name;
    const float* values;
    int stride = 3;
};

/// The bytes of an EXR file of `width` x `height` pixels holding `channels` (names distinct, at
/// most 255 bytes; the file lists them sorted by name, as OpenEXR requires). Halves are the
/// nearest to each value, clamped to +-65504 (the largest finite half: an infinity would spread
/// over the image under a compositor's blur), a NaN written as 0; floats are written as they are.
std::vector<unsigned char> encode_exr(int width, int height, std::vector<ExrChannelValues> channels, ExrPixelType type);

}  // namespace steadylight
