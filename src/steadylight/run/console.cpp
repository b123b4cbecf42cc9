// The console sink (log lines under a status line) and the progress bar (console.h).
#include "steadylight/run/console.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include <fmt/format.h>
#include <spdlog/sinks/base_sink.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/spdlog.h>

#include "steadylight/base/error.h"

namespace steadylight {
namespace {

/// Log lines on stdout (warnings and errors on stderr) below which a status line on stderr is
/// kept: cleared before each line and redrawn after it.
class ConsoleSink final : public spdlog::sinks::base_sink<std::mutex> {
public:
    bool is_terminal() const { return m_terminal; }

    void set_status(const std::string& line) {
        const std::lock_guard lock(mutex_);
        clear_status();
        m_status = line;
        draw_status();
    }

protected:
    void sink_it_(const spdlog::details::log_msg& msg) override {
        spdlog::memory_buf_t text;
        formatter_->format(msg, text);
        clear_status();
        FILE* out = msg.level >= spdlog::level::warn ? stderr : stdout;
        std::fwrite(text.data(), 1, text.size(), out);
        std::fflush(out);
        draw_status();
    }
    void flush_() override { std::fflush(stdout); }

private:
    void clear_status() {
        if (m_terminal && !m_status.empty()) std::fputs("\r\033[K", stderr);
    }
    void draw_status() {
        if (!m_terminal || m_status.empty()) return;
        // A line longer than the terminal would wrap, and "\r" could not erase it.
        winsize size{};
        const size_t columns = ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 1 ? size.ws_col : 80;
        std::fputs(m_status.substr(0, columns - 1).c_str(), stderr);
        std::fflush(stderr);
    }

    bool m_terminal = isatty(STDERR_FILENO) != 0;
    std::string m_status;
};

std::shared_ptr<ConsoleSink> g_console_sink;

spdlog::level::level_enum parse_level(const std::string& name) {
    using enum spdlog::level::level_enum;
    const std::pair<const char*, spdlog::level::level_enum> levels[] = {
        {"trace", trace}, {"debug", debug}, {"info", info}, {"warn", warn}, {"error", err}};
    for (const auto& [level_name, level] : levels)
        if (name == level_name) return level;
    throw InputError("--log-level", "unknown level \"" + name + "\" (trace, debug, info, warn, error)");
}

}  // namespace

void setup_logging(const LogOptions& options) {
    const spdlog::level::level_enum level = parse_level(options.level);
    auto console = std::make_shared<ConsoleSink>();
    console->set_pattern("[%H:%M:%S] [%l] %v");
    console->set_level(options.quiet ? spdlog::level::err : level);
    std::vector<spdlog::sink_ptr> sinks{console};
    if (!options.file.empty()) {
        try {
            sinks.push_back(std::make_shared<spdlog::sinks::basic_file_sink_mt>(options.file, false));
        } catch (const spdlog::spdlog_ex& e) {
            throw InputError("--log", e.what());
        }
        sinks.back()->set_level(level);
    }
    auto logger = std::make_shared<spdlog::logger>("steadylight", sinks.begin(), sinks.end());
    logger->set_level(level);
    logger->flush_on(spdlog::level::trace);  // a log file is whole up to the last line, even after Ctrl-C twice
    spdlog::set_default_logger(logger);
    g_console_sink = console;
}

std::string format_duration(double seconds) {
    const long s = long(std::max(0.0, seconds) + 0.5);
    return s >= 3600 ? fmt::format("{}:{:02d}:{:02d}", s / 3600, (s / 60) % 60, s % 60)
                     : fmt::format("{}:{:02d}", s / 60, s % 60);
}

ConsoleProgress::ConsoleProgress(int total_frames, bool enabled)
    : m_total_frames(total_frames), m_enabled(enabled && g_console_sink && g_console_sink->is_terminal()) {}

ConsoleProgress::~ConsoleProgress() {
    if (m_enabled) g_console_sink->set_status("");
}

void ConsoleProgress::begin_frame(int frame) {
    {
        const std::lock_guard lock(m_mutex);
        m_frame = frame;
        m_phase.clear();
        m_work_fraction = -1;
        m_frame_start = Clock::now();
    }
    redraw(true);
}

void ConsoleProgress::finish_frame() {
    {
        const std::lock_guard lock(m_mutex);
        ++m_frames_done;
        m_frames_seconds += std::chrono::duration<double>(Clock::now() - m_frame_start).count();
        m_frame = -1;
    }
    redraw(true);
}

void ConsoleProgress::phase(std::string_view name) {
    {
        const std::lock_guard lock(m_mutex);
        m_phase = name;
        m_work_fraction = -1;
    }
    redraw(true);
}

void ConsoleProgress::work(long done, long total) {
    {
        const std::lock_guard lock(m_mutex);
        m_work_fraction = total > 0 ? double(done) / double(total) : 0;
    }
    redraw(false);
}

std::string ConsoleProgress::status_line() {
    const std::lock_guard lock(m_mutex);
    const Clock::time_point now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - m_start).count();
    constexpr int width = 20;
    const double fraction = m_total_frames > 0 ? double(m_frames_done) / m_total_frames : 1.0;
    const int filled = std::clamp(int(fraction * width), 0, width);
    // ETA from the mean time of the finished frames, less what the current one has taken.
    std::string eta = "?";
    if (m_frames_done > 0) {
        const double current = m_frame >= 0 ? std::chrono::duration<double>(now - m_frame_start).count() : 0;
        eta = format_duration(m_frames_seconds / m_frames_done * (m_total_frames - m_frames_done) - current);
    }
    // The phase comes last: a narrow terminal cuts it off first.
    std::string line = fmt::format("[{}{}] {}/{} frames  {} elapsed, ETA {}", std::string(size_t(filled), '#'),
                                   std::string(size_t(width - filled), '.'), m_frames_done, m_total_frames,
                                   format_duration(elapsed), eta);
    if (m_frame >= 0) line += fmt::format("  frame {}: {}", m_frame, m_phase.empty() ? "starting" : m_phase);
    if (m_frame >= 0 && m_work_fraction >= 0) line += fmt::format(" {:.0f}%", 100 * m_work_fraction);
    return line;
}

void ConsoleProgress::redraw(bool force) {
    if (!m_enabled) return;
    {
        // At most ten redraws a second, but every phase change.
        const std::lock_guard lock(m_mutex);
        const Clock::time_point now = Clock::now();
        if (!force && now - m_last_draw < std::chrono::milliseconds(100)) return;
        m_last_draw = now;
    }
    g_console_sink->set_status(status_line());
}

}  // namespace steadylight
