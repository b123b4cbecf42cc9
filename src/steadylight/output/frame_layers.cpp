// The EXR layer list of a frame (frame_layers.h).
#include "steadylight/output/frame_layers.h"

namespace steadylight {

std::vector<ExrLayer> frame_exr_layers(const Image& beauty, const std::vector<NamedImage>& aovs) {
    // The beauty twice: plain viewers show only the unnamed R, G, B, while Blender's Image node
    // and Nuke's layer menu list layers by their prefix. It adds a tenth or less to the file.
    std::vector<ExrLayer> layers{{"", &beauty}, {"beauty", &beauty}};
    for (const NamedImage& aov : aovs) layers.push_back({aov.name, &aov.image, aov.grey});
    return layers;
}

}  // namespace steadylight
