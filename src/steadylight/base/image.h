// A linear RGB image, row-major from the top-left pixel.
#pragma once

#include <string>
#include <vector>

#include "steadylight/base/color.h"
#include "steadylight/base/unfilled_allocator.h"

namespace steadylight {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<Rgb, UnfilledAllocator<Rgb>> pixels;

    Image() = default;
    /// A black image.
    Image(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h), Rgb{}) {}
    /// An image whose every pixel the caller writes before anything reads it. Not zeroed first:
    /// at production sizes that is a serial pass over tens of megabytes, mostly page faults,
    /// while the threads that fill the image touch its memory anyway.
    static Image unfilled(int w, int h) {
        Image image;
        image.width = w, image.height = h;
        image.pixels.resize(size_t(w) * size_t(h));
        return image;
    }
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
