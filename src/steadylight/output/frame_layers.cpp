// The EXR layer list of a frame (frame_layers.h).
#include "steadylight/output/frame_layers.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string_view>

#include "steadylight/base/parallel.h"

namespace steadylight {

std::vector<ExrLayer> frame_exr_layers(const Image& beauty, const std::vector<NamedImage>& aovs, const Image* alpha) {
    // The beauty twice: plain viewers show only the unnamed R, G, B, while Blender's Image node
    // and Nuke's layer menu list layers by their prefix. One layer more: a fourteenth of a
    // localized frame's file, but a path-traced frame, which has no other layer, doubles.
    std::vector<ExrLayer> layers{{"", &beauty, false, alpha}, {"beauty", &beauty, false, alpha}};
    for (const NamedImage& aov : aovs) layers.push_back({aov.name, &aov.image, aov.grey});
    return layers;
}

std::vector<ExrLayer> blender_exr_layers(const std::string& view_layer, const Image& beauty,
                                         const std::vector<NamedImage>& aovs, const Image& alpha) {
    std::vector<ExrLayer> layers{{view_layer + ".Combined", &beauty, false, &alpha}};
    for (const NamedImage& aov : aovs)
        layers.push_back({view_layer + "." + aov.name, &aov.image, aov.grey, nullptr, "X"});
    return layers;
}

namespace {

/// Whether every channel value of `image` is finite (its exponent bits not all set): a loop
/// without branches, which the compiler vectorizes, since finite values are the rule.
bool all_finite(const Image& image) {
    const auto* values = reinterpret_cast<const unsigned char*>(image.pixels.data());
    const size_t count = image.pixels.size() * 3;
    constexpr uint32_t exponent = 0x7f800000u;
    uint32_t non_finite = 0;
    for (size_t i = 0; i < count; ++i) {
        uint32_t bits;
        std::memcpy(&bits, values + 4 * i, 4);
        non_finite |= uint32_t((bits & exponent) == exponent);
    }
    return non_finite == 0;
}

void replace_non_finite(Image& image, std::string_view layer, NonFiniteValues& found) {
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (float* value : {&image.at(x, y).r, &image.at(x, y).g, &image.at(x, y).b}) {
                if (std::isfinite(*value)) continue;
                if (found.count++ == 0) found.first_layer = std::string(layer), found.first_x = x, found.first_y = y;
                *value = 0;
            }
}

}  // namespace

NonFiniteValues replace_non_finite(Image& beauty, std::vector<NamedImage>& aovs) {
    // The layers checked side by side (a production frame's dozen layers take tens of
    // milliseconds one by one, between the frame's rendering and the next), then those that
    // hold a non-finite value mended in order, so that the first one found is the same.
    struct Layer {
        Image* image;
        std::string_view name;
    };
    std::vector<Layer> layers{{&beauty, "beauty"}};
    for (NamedImage& aov : aovs) layers.push_back({&aov.image, aov.name});
    std::vector<uint8_t> finite(layers.size());
    parallel_for_chunks(long(layers.size()), 1, [&](long begin, long end) {
        for (long i = begin; i < end; ++i) finite[size_t(i)] = all_finite(*layers[size_t(i)].image);
    });
    NonFiniteValues found;
    for (size_t i = 0; i < layers.size(); ++i)
        if (!finite[i]) replace_non_finite(*layers[i].image, layers[i].name, found);
    return found;
}

}  // namespace steadylight
