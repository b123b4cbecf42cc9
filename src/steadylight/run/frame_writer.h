// Writing a frame while the next one renders (issue: writing off the critical path). Encoding
// and compressing a frame's EXR layers and PNGs took about 1.2 s of a 7 s frame at 1280x960 on
// one thread; here it runs on a thread of its own, overlapping the next frame's rendering.
// At most one frame waits to be written, so memory holds at most two frames' images. A frame's
// manifest is still written last, inside its write (run/frame_manifest.h): a frame cut short has
// none. Writes happen in frame order, and a write's error (a full disk) reaches the renderer at
// the next frame or at the end, as the exception it was.
#pragma once

#include <functional>
#include <future>
#include <optional>

namespace steadylight {

class FrameWriter {
public:
    /// `on_written(frame)` runs on the caller's thread once a frame's write has finished.
    explicit FrameWriter(std::function<void(int frame)> on_written) : m_on_written(std::move(on_written)) {}
    FrameWriter(const FrameWriter&) = delete;
    FrameWriter& operator=(const FrameWriter&) = delete;
    /// Waits for a pending write (errors are lost here: call finish() first).
    ~FrameWriter();

    /// Waits for the previous write (rethrowing its error), then starts `write` for `frame`.
    template <class Write>
    void write(int frame, Write&& write) {
        finish();
        m_pending = std::async(std::launch::async, std::forward<Write>(write));
        m_pending_frame = frame;
    }

    /// Waits for the pending write, if any; rethrows its error.
    void finish();
    /// finish() while another error is on its way out (Ctrl-C): the pending frame is still
    /// written, and its own error, if any, only logged.
    void finish_quietly() noexcept;

private:
    std::function<void(int)> m_on_written;
    std::future<void> m_pending;
    std::optional<int> m_pending_frame;
};

}  // namespace steadylight
