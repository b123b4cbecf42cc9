// A linear RGB image, row-major from the top-left pixel.
#pragma once

#include <string>
#include <vector>

#include "steadylight/base/color.h"

namespace steadylight {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<Rgb> pixels;

    Image() = default;
    Image(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h)) {}
    Rgb& at(int x, int y) { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
    const Rgb& at(int x, int y) const { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
};

/// An image under the name it is written with, such as one AOV layer of a frame. `grey` when it
/// holds one value per pixel (a mask, a count), written as a single channel.
struct NamedImage {
    std::string name;
    Image image;
    bool grey = false;
};

}  // namespace steadylight
