// The console of a render: the log (spdlog) and, on a terminal, a progress bar under it.
// setup_logging() installs the log: a console sink (stdout) at --log-level, or errors only with
// --quiet, plus an optional file sink (--log FILE, appended to). ConsoleProgress listens to the
// render's checkpoints (base/checkpoint.h) and keeps one status line on stderr — frames done,
// the current frame's phase and how far its parallel loop got, elapsed time and ETA — which the
// console sink clears before each log line and redraws after it. Off a terminal (CI, pipes)
// there is no bar: render_animation() logs one summary line per frame instead, in both cases.
#pragma once

#include <chrono>
#include <memory>
#include <mutex>
#include <string>

#include "steadylight/base/checkpoint.h"

namespace steadylight {

struct LogOptions {
    std::string level = "info";  // trace, debug, info, warn, error
    std::string file;            // also log to this file (appended), at `level`
    bool quiet = false;          // the console shows errors only
};

/// Makes the default spdlog logger write to the console (and `options.file`). Throws InputError
/// for an unknown level or a log file that cannot be opened.
void setup_logging(const LogOptions& options);

/// Progress of a render over frames and over the phases inside a frame, drawn as a status
/// line on stderr when it is a terminal and `enabled`; otherwise silent.
class ConsoleProgress final : public CheckpointListener {
public:
    ConsoleProgress(int total_frames, bool enabled);
    ~ConsoleProgress() override;

    void begin_frame(int frame);
    void finish_frame();
    void phase(std::string_view name) override;
    void work(long done, long total) override;

    /// The status line as it would be drawn now (for tests).
    std::string status_line();

private:
    using Clock = std::chrono::steady_clock;
    void redraw(bool force);

    int m_total_frames;
    bool m_enabled;
    std::mutex m_mutex;
    int m_frames_done = 0;
    int m_frame = -1;
    std::string m_phase;
    double m_work_fraction = -1;  // of the phase's current parallel loop; -1 before the first report
    Clock::time_point m_start = Clock::now();
    Clock::time_point m_frame_start = m_start;
    Clock::time_point m_last_draw = m_start;
    double m_frames_seconds = 0;  // wall time of the finished frames
};

/// "1:05" or "1:02:05".
std::string format_duration(double seconds);

}  // namespace steadylight
