// Progress of a long render on the console: on a terminal, one bar redrawn in place with the
// elapsed time and an ETA; otherwise (logs, CI) one plain line per finished frame.
#pragma once

#include <chrono>
#include <mutex>
#include <string>

namespace steadylight {

class Progress {
public:
    /// `total_frames` frames to render; `enabled` false silences everything.
    Progress(int total_frames, bool enabled);

    /// Within the current frame, `done` of `total` work items are finished. Thread-safe.
    void update_frame(int done, int total);
    /// The current frame is finished; `summary` describes it (time, file).
    void finish_frame(const std::string& summary);

private:
    void draw(double frame_fraction);
    double elapsed_s() const;

    int m_total_frames;
    int m_frames_done = 0;
    bool m_enabled;
    bool m_is_terminal;
    std::chrono::steady_clock::time_point m_start;
    std::chrono::steady_clock::time_point m_last_draw;
    std::mutex m_mutex;
};

}  // namespace steadylight
