// The EXR layer list of a frame (frame_layers.h).
#include "steadylight/output/frame_layers.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <variant>

#include "steadylight/base/parallel.h"

namespace steadylight {

std::vector<ExrLayer> frame_exr_layers(const Image& beauty, const std::vector<NamedImage>& aovs, const Image* alpha) {
    // The beauty twice: plain viewers show only the unnamed R, G, B, while Blender's Image node
    // and Nuke's layer menu list layers by their prefix. One layer more: a fourteenth of a
    // localized frame's file, but a path-traced frame, which has no other layer, doubles.
    std::vector<ExrLayer> layers{{"", &beauty, nullptr, alpha}, {"beauty", &beauty, nullptr, alpha}};
    for (const NamedImage& aov : aovs) layers.push_back({aov.name, std::get_if<Image>(&aov.image), aov.grey()});
    return layers;
}

std::vector<ExrLayer> blender_exr_layers(const std::string& view_layer, const Image& beauty,
                                         const std::vector<NamedImage>& aovs, const Image& alpha) {
    std::vector<ExrLayer> layers{{view_layer + ".Combined", &beauty, nullptr, &alpha}};
    for (const NamedImage& aov : aovs)
        layers.push_back({view_layer + "." + aov.name, std::get_if<Image>(&aov.image), aov.grey(), nullptr, "X"});
    return layers;
}

namespace {

/// A layer's channel values, pixel by pixel from the top-left, `channels` a pixel.
struct LayerValues {
    float* values;
    size_t count;
    int width;
    int channels;
    std::string_view name;
};

LayerValues values_of(Image& image, std::string_view name) {
    static_assert(sizeof(Rgb) == 3 * sizeof(float));
    return {reinterpret_cast<float*>(image.pixels.data()), image.pixels.size() * 3, image.width, 3, name};
}

LayerValues values_of(GreyImage& image, std::string_view name) {
    return {image.pixels.data(), image.pixels.size(), image.width, 1, name};
}

/// Whether every value of `layer` is finite (its exponent bits not all set): a loop without
/// branches, which the compiler vectorizes, since finite values are the rule.
bool all_finite(const LayerValues& layer) {
    const auto* values = reinterpret_cast<const unsigned char*>(layer.values);
    constexpr uint32_t exponent = 0x7f800000u;
    uint32_t non_finite = 0;
    for (size_t i = 0; i < layer.count; ++i) {
        uint32_t bits;
        std::memcpy(&bits, values + 4 * i, 4);
        non_finite |= uint32_t((bits & exponent) == exponent);
    }
    return non_finite == 0;
}

void replace_non_finite(const LayerValues& layer, NonFiniteValues& found) {
    for (size_t i = 0; i < layer.count; ++i) {
        if (std::isfinite(layer.values[i])) continue;
        if (found.count++ == 0) {
            const size_t pixel = i / size_t(layer.channels);
            found.first_layer = std::string(layer.name);
            found.first_x = int(pixel % size_t(layer.width)), found.first_y = int(pixel / size_t(layer.width));
        }
        layer.values[i] = 0;
    }
}

}  // namespace

NonFiniteValues replace_non_finite(Image& beauty, std::vector<NamedImage>& aovs) {
    // The layers checked side by side (a production frame's dozen layers take tens of
    // milliseconds one by one, between the frame's rendering and the next), then those that
    // hold a non-finite value mended in order, so that the first one found is the same.
    std::vector<LayerValues> layers{values_of(beauty, "beauty")};
    for (NamedImage& aov : aovs)
        std::visit([&](auto& image) { layers.push_back(values_of(image, aov.name)); }, aov.image);
    std::vector<uint8_t> finite(layers.size());
    parallel_for_chunks(long(layers.size()), 1, [&](long begin, long end) {
        for (long i = begin; i < end; ++i) finite[size_t(i)] = all_finite(layers[size_t(i)]);
    });
    NonFiniteValues found;
    for (size_t i = 0; i < layers.size(); ++i)
        if (!finite[i]) replace_non_finite(layers[i], found);
    return found;
}

}  // namespace steadylight
