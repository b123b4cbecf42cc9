// Writing frames on a thread of their own (frame_writer.h).
#include "steadylight/run/frame_writer.h"

#include <exception>

#include <spdlog/spdlog.h>

namespace steadylight {

FrameWriter::~FrameWriter() { finish_quietly(); }

void FrameWriter::finish() {
    if (!m_pending_frame) return;
    const int frame = *m_pending_frame;
    m_pending_frame.reset();
    m_pending.get();  // rethrows the write's error
    m_on_written(frame);
}

void FrameWriter::finish_quietly() noexcept {
    try {
        finish();
    } catch (const std::exception& e) {
        spdlog::error("writing a frame failed: {}", e.what());
    } catch (...) {
        spdlog::error("writing a frame failed");
    }
}

}  // namespace steadylight
