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

/// A scene placed at one frame with everything a FrameContext refers to, built from scratch:
/// for rendering single frames (tests, benchmarks). An animation reuses one RayTracer instead.
struct PreparedFrame {
    const Scene& scene;
    FrameState state;
    RayTracer tracer;
    LightSet lights;
    std::vector<std::unique_ptr<Bsdf>> bsdfs;

    PreparedFrame(const Scene& s, int frame)
        : scene(s), state(s.evaluate(frame)), tracer(s, state), lights(s, state), bsdfs(make_bsdfs(s)) {}
    FrameContext context() const { return {scene, state, tracer, lights, bsdfs}; }
};

}  // namespace steadylight
