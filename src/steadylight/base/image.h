// A linear RGB image and a grey one, row-major from the top-left pixel.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "steadylight/base/color.h"
#include "steadylight/base/unfilled_allocator.h"

namespace steadylight {

/// Pixels of one kind, row-major from the top-left one.
template <class Pixel>
struct PixelImage {
    int width = 0;
    int height = 0;
    std::vector<Pixel, UnfilledAllocator<Pixel>> pixels;

    PixelImage() = default;
    /// A black image.
    PixelImage(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h), Pixel{}) {}
    /// An image whose every pixel the caller writes before anything reads it. Not zeroed first:
    /// at production sizes that is a serial pass over tens of megabytes, mostly page faults,
    /// while the threads that fill the image touch its memory anyway.
    static PixelImage unfilled(int w, int h) {
        PixelImage image;
        image.width = w, image.height = h;
        image.pixels.resize(size_t(w) * size_t(h));
        return image;
    }
    Pixel& at(int x, int y) { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
    const Pixel& at(int x, int y) const { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
};

using Image = PixelImage<Rgb>;
/// One value a pixel (a mask, a count, a ratio): a third of an Image's bytes, for the layers
/// that a colour would hold three times.
using GreyImage = PixelImage<float>;

/// `grey` with its value in each of the three channels (for an 8-bit picture of it).
inline Image colour_of(const GreyImage& grey) {
    Image image = Image::unfilled(grey.width, grey.height);
    for (size_t i = 0; i < grey.pixels.size(); ++i) image.pixels[i] = {grey.pixels[i], grey.pixels[i], grey.pixels[i]};
    return image;
}

/// An image under the name it is written with, such as one AOV layer of a frame: a colour one, or
/// a grey one, written as a single channel.
struct NamedImage {
    std::string name;
    std::variant<Image, GreyImage> image;

    const GreyImage* grey() const { return std::get_if<GreyImage>(&image); }
    size_t pixel_count() const {
        return std::visit([](const auto& pixels) { return pixels.pixels.size(); }, image);
    }
    /// Pixel `i`, row-major; a grey one with its value in each channel.
    Rgb colour_at(size_t i) const {
        if (const GreyImage* g = grey()) return {g->pixels[i], g->pixels[i], g->pixels[i]};
        return std::get<Image>(image).pixels[i];
    }
};

}  // namespace steadylight
