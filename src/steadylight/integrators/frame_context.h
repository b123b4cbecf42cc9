// Everything an integrator reads to render one frame: the scene, where things are, the ray
// tracer placed at that frame, its lights and the materials' BSDFs.
#pragma once

#include <memory>
#include <vector>

#include "steadylight/scene/scene.h"
#include "steadylight/shading/bsdf.h"
#include "steadylight/shading/light.h"
#include "steadylight/trace/ray_tracer.h"

namespace steadylight {

struct FrameContext {
    const Scene& scene;
    const FrameState& frame;
    const RayTracer& tracer;
    const LightSet& lights;
    const std::vector<std::unique_ptr<Bsdf>>& bsdfs;  // one per material

    const Bsdf& bsdf_of(int object) const { return *bsdfs[size_t(scene.object(object).material)]; }
};

/// One BSDF per material of the scene, in material order.
std::vector<std::unique_ptr<Bsdf>> make_bsdfs(const Scene& scene);

}  // namespace steadylight
