// `--video FILE.mp4`: after the frames are written, the PNG sequence is encoded with the
// `ffmpeg` program (H.264 through libx264, yuv420p so that every player shows it, the scene's
// frame rate, odd sizes padded to even, PNGs with alpha laid over black). ffmpeg runs through posix_spawn with an
// argument vector, never a shell, so paths with spaces or quotes need no quoting. The video is written under a
// temporary name and renamed when ffmpeg succeeds.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace steadylight {

struct VideoJob {
    std::string out_dir;  // where the PNGs are: <out_dir>/<scene_name>_<frame:04>.png
    std::string scene_name;
    int first_frame = 0;
    int frame_count = 0;
    float fps = 24;
    std::string output;  // the .mp4 to write
    /// The PNGs have alpha (a transparent background): the video, which has none, shows them
    /// over black, their colours multiplied by their alpha as a viewer lays them over black
    /// (ffmpeg would drop the alpha, and edges would lose their antialiasing).
    bool alpha = false;
};

/// The path of the `ffmpeg` executable found in PATH, or nothing.
std::optional<std::string> find_ffmpeg();

/// First and last frame when `frames` are consecutive and increasing, else nothing.
std::optional<std::pair<int, int>> contiguous_span(const std::vector<int>& frames);

/// Checks, before anything is rendered, that a video of `frames` can be made: ffmpeg is
/// installed and the frames are consecutive. Throws InputError naming `--video` otherwise.
void check_video_possible(const std::vector<int>& frames);

/// The ffmpeg arguments (argv without the program) that encode `job` into `temporary_output`.
std::vector<std::string> ffmpeg_arguments(const VideoJob& job, const std::string& temporary_output);

/// Runs ffmpeg and renames its output onto `job.output`. Throws InputError naming `--video` when
/// ffmpeg is missing, cannot start, or exits with an error (its own messages are on stderr).
void encode_video(const VideoJob& job);

}  // namespace steadylight
