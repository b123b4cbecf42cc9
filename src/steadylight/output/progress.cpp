#include "steadylight/output/progress.h"

#include <unistd.h>

#include <cstdio>

#include <fmt/format.h>

namespace steadylight {
namespace {

std::string format_duration(double seconds) {
    const long s = long(seconds + 0.5);
    return s >= 3600 ? fmt::format("{}:{:02d}:{:02d}", s / 3600, (s / 60) % 60, s % 60)
                     : fmt::format("{}:{:02d}", s / 60, s % 60);
}

}  // namespace

Progress::Progress(int total_frames, bool enabled)
    : m_total_frames(total_frames),
      m_enabled(enabled),
      m_is_terminal(isatty(fileno(stderr)) != 0),
      m_start(std::chrono::steady_clock::now()),
      m_last_draw(m_start) {}

double Progress::elapsed_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
}

void Progress::update_frame(int done, int total) {
    if (!m_enabled || !m_is_terminal) return;
    const std::lock_guard lock(m_mutex);
    // Redraw at most ten times a second.
    const auto now = std::chrono::steady_clock::now();
    if (done < total && now - m_last_draw < std::chrono::milliseconds(100)) return;
    m_last_draw = now;
    draw(total > 0 ? double(done) / total : 0.0);
}

void Progress::draw(double frame_fraction) {
    const double fraction = (m_frames_done + frame_fraction) / m_total_frames;
    constexpr int width = 30;
    const int filled = int(fraction * width);
    const double elapsed = elapsed_s();
    const std::string eta = fraction > 0 ? format_duration(elapsed / fraction - elapsed) : "?";
    std::fprintf(stderr, "\r[%s%s] %5.1f%%  frame %d/%d  %s elapsed, ETA %s ",
                 std::string(size_t(filled), '#').c_str(), std::string(size_t(width - filled), '.').c_str(),
                 100 * fraction, std::min(m_frames_done + 1, m_total_frames), m_total_frames,
                 format_duration(elapsed).c_str(), eta.c_str());
    std::fflush(stderr);
}

void Progress::finish_frame(const std::string& summary) {
    if (!m_enabled) return;
    const std::lock_guard lock(m_mutex);
    ++m_frames_done;
    // On a terminal the summary line goes above the bar, which is then redrawn.
    if (m_is_terminal) std::fprintf(stderr, "\r\033[K");
    std::fprintf(stderr, "%s\n", summary.c_str());
    if (m_is_terminal && m_frames_done < m_total_frames) draw(0);
    std::fflush(stderr);
}

}  // namespace steadylight
