// Making FrameContexts (frame_context.h).
#include "steadylight/shading/frame_context.h"

namespace steadylight {
namespace {

/// `state`, once `tracer` is moved there.
const FrameState& place(RayTracer& tracer, const FrameState& state) {
    tracer.set_frame(state);
    return state;
}

}  // namespace

Bsdfs make_bsdfs(const Scene& scene) {
    Bsdfs bsdfs;
    for (const MaterialDesc& material : scene.desc().materials) bsdfs.push_back(make_bsdf(material));
    return bsdfs;
}

PlacedFrame::PlacedFrame(const Scene& scene, RayTracer& tracer, const Bsdfs& bsdfs, int frame)
    : m_state(scene.evaluate(frame)),
      m_lights(scene, place(tracer, m_state)),
      m_mirrors(flat_mirrors(scene, m_state)),
      m_context{scene, m_state, tracer, m_lights, bsdfs, m_mirrors} {}

PreparedFrame::PreparedFrame(const Scene& scene, int frame)
    : m_tracer(scene, scene.evaluate(frame)), m_bsdfs(make_bsdfs(scene)), m_placed(scene, m_tracer, m_bsdfs, frame) {}

}  // namespace steadylight
