// The EXR layer list of a frame (frame_layers.h).
#include "steadylight/output/frame_layers.h"

#include <algorithm>
#include <array>

namespace steadylight {

bool is_scalar_layer(const std::string& name) {
    static const std::array<std::string, 4> scalar = {"influence", "records", "static_records", "dynamic_records"};
    return std::find(scalar.begin(), scalar.end(), name) != scalar.end();
}

std::vector<ExrLayer> frame_exr_layers(const Image& beauty, const std::vector<std::pair<std::string, Image>>& aovs) {
    // The beauty twice: plain viewers show only the unnamed R, G, B, while Blender's Image node
    // and Nuke's layer menu list layers by their prefix. It adds a tenth or less to the file.
    std::vector<ExrLayer> layers{{"", &beauty}, {"beauty", &beauty}};
    for (const auto& [name, image] : aovs) layers.push_back({name, &image, is_scalar_layer(name)});
    return layers;
}

}  // namespace steadylight
