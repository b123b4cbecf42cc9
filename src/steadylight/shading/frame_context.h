// Everything a pass reads to render one frame: the scene, where things are, the ray tracer
// placed at that frame, its lights and the materials' BSDFs. PlacedFrame is the one place a
// FrameContext is made: it places the scene (and a shared ray tracer) at a frame.
#pragma once

#include <memory>
#include <vector>

#include "steadylight/scene/scene.h"
#include "steadylight/shading/bsdf.h"
#include "steadylight/shading/light.h"
#include "steadylight/shading/mirror_images.h"
#include "steadylight/trace/ray_tracer.h"

namespace steadylight {

using Bsdfs = std::vector<std::unique_ptr<Bsdf>>;  // one per material, in material order

struct FrameContext {
    const Scene& scene;
    const FrameState& frame;
    const RayTracer& tracer;
    const LightSet& lights;
    const Bsdfs& bsdfs;
    const std::vector<MirrorPlane>&
        mirrors;  // the flat static mirrors, whose images of the lights glossy surfaces sample

    const Bsdf& bsdf_of(int object) const { return *bsdfs[size_t(scene.object(object).material)]; }
};

/// One BSDF per material of the scene, in material order.
Bsdfs make_bsdfs(const Scene& scene);

/// The scene at one frame: evaluates the frame, moves `tracer` there (only the dynamic objects
/// move; an animation reuses one tracer) and finds the frame's lights and flat mirrors. While it
/// lives, `tracer` must stay at this frame. Never copied or moved: its context refers to its members.
class PlacedFrame {
public:
    PlacedFrame(const Scene& scene, RayTracer& tracer, const Bsdfs& bsdfs, int frame);
    PlacedFrame(const PlacedFrame&) = delete;
    PlacedFrame& operator=(const PlacedFrame&) = delete;

    const FrameContext& context() const { return m_context; }

private:
    FrameState m_state;
    LightSet m_lights;
    std::vector<MirrorPlane> m_mirrors;
    FrameContext m_context;
};

/// A scene placed at one frame with a ray tracer and BSDFs of its own, built from scratch: for
/// rendering single frames (tests, benchmarks).
class PreparedFrame {
public:
    PreparedFrame(const Scene& scene, int frame);

    const FrameContext& context() const { return m_placed.context(); }

private:
    RayTracer m_tracer;
    Bsdfs m_bsdfs;
    PlacedFrame m_placed;
};

}  // namespace steadylight
