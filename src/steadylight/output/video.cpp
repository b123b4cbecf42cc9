// Encoding the PNG sequence with ffmpeg (video.h).
#include "steadylight/output/video.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "steadylight/base/error.h"

extern char** environ;

namespace steadylight {
namespace {

namespace fs = std::filesystem;

/// `text` with every '%' doubled, so that ffmpeg's image2 pattern takes it literally.
std::string escape_percent(const std::string& text) {
    std::string escaped;
    for (const char c : text) escaped += c == '%' ? std::string("%%") : std::string(1, c);
    return escaped;
}

/// Runs `program` with `arguments` (no shell) and returns its exit status, or -1 when it could
/// not start or was killed by a signal.
int run_program(const std::string& program, const std::vector<std::string>& arguments) {
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(program.c_str()));
    for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
    argv.push_back(nullptr);
    pid_t pid = 0;
    if (posix_spawn(&pid, program.c_str(), nullptr, nullptr, argv.data(), environ) != 0) return -1;
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

std::optional<std::string> find_ffmpeg() {
    const char* path = std::getenv("PATH");
    if (!path) return std::nullopt;
    const std::string dirs = path;
    for (size_t start = 0; start <= dirs.size();) {
        const size_t end = std::min(dirs.find(':', start), dirs.size());
        const fs::path candidate = fs::path(end > start ? dirs.substr(start, end - start) : ".") / "ffmpeg";
        if (fs::is_regular_file(candidate) && access(candidate.c_str(), X_OK) == 0) return candidate.string();
        start = end + 1;
    }
    return std::nullopt;
}

std::optional<std::pair<int, int>> contiguous_span(const std::vector<int>& frames) {
    if (frames.empty()) return std::nullopt;
    for (size_t i = 1; i < frames.size(); ++i)
        if (frames[i] != frames[i - 1] + 1) return std::nullopt;
    return std::pair{frames.front(), frames.back()};
}

void check_video_possible(const std::vector<int>& frames) {
    if (!find_ffmpeg())
        throw InputError("--video",
                         "the ffmpeg program is not installed (not found in PATH); install it "
                         "(Debian: apt-get install ffmpeg) or render without --video");
    if (!contiguous_span(frames))
        throw InputError("--video", "a video needs consecutive frames (--frames without gaps or steps, such as A-B)");
}

std::vector<std::string> ffmpeg_arguments(const VideoJob& job, const std::string& temporary_output) {
    const std::string pattern =
        (fs::path(escape_percent(job.out_dir)) / (escape_percent(job.scene_name) + "_%04d.png")).string();
    return {"-hide_banner", "-loglevel", "error", "-nostdin", "-y", "-framerate", fmt::format("{}", job.fps),
            "-start_number", std::to_string(job.first_frame), "-i", pattern, "-frames:v",
            std::to_string(job.frame_count),
            // H.264 in yuv420p needs even sizes: pad odd ones with one black row or column.
            "-vf", std::string(job.alpha ? "premultiply=inplace=1," : "") + "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v",
            "libx264", "-pix_fmt", "yuv420p", "-crf", "18", "-movflags", "+faststart", "-f", "mp4", temporary_output};
}

void encode_video(const VideoJob& job) {
    const std::optional<std::string> ffmpeg = find_ffmpeg();
    if (!ffmpeg) throw InputError("--video", "cannot write " + job.output + ": ffmpeg is not installed");
    const std::string temporary = job.output + ".partial";
    // A folder that cannot be made shows up as ffmpeg's own error about the file, just below.
    std::error_code ignored;
    if (const fs::path folder = fs::path(job.output).parent_path(); !folder.empty())
        fs::create_directories(folder, ignored);
    const int status = run_program(*ffmpeg, ffmpeg_arguments(job, temporary));
    if (status != 0) {
        fs::remove(temporary, ignored);
        throw InputError(
            "--video",
            fmt::format("cannot write {}: ffmpeg {} (its messages are above); the frames are written", job.output,
                        status < 0 ? "did not run to completion" : fmt::format("exited with status {}", status)));
    }
    fs::rename(temporary, job.output);
}

}  // namespace steadylight
