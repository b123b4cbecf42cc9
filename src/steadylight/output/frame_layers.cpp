// The EXR layer list of a frame (frame_layers.h).
#include "steadylight/output/frame_layers.h"

#include <cmath>

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

void replace_non_finite(Image& image, const std::string& layer, NonFiniteValues& found) {
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (float* value : {&image.at(x, y).r, &image.at(x, y).g, &image.at(x, y).b}) {
                if (std::isfinite(*value)) continue;
                if (found.count++ == 0) found.first_layer = layer, found.first_x = x, found.first_y = y;
                *value = 0;
            }
}

}  // namespace

NonFiniteValues replace_non_finite(Image& beauty, std::vector<NamedImage>& aovs) {
    NonFiniteValues found;
    replace_non_finite(beauty, "beauty", found);
    for (NamedImage& aov : aovs) replace_non_finite(aov.image, aov.name, found);
    return found;
}

}  // namespace steadylight
