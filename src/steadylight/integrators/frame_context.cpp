#include "steadylight/integrators/frame_context.h"

namespace steadylight {

std::vector<std::unique_ptr<Bsdf>> make_bsdfs(const Scene& scene) {
    std::vector<std::unique_ptr<Bsdf>> bsdfs;
    for (const MaterialDesc& material : scene.desc().materials) bsdfs.push_back(make_bsdf(material));
    return bsdfs;
}

}  // namespace steadylight
