// Which frames a render covers: the `--frames` text ("7", "0-59", "10-20:2", "1,5,10-20:5")
// parsed into spans, then checked against the scene and expanded into a sorted list without
// duplicates. render_animation() walks that list; a segment's static pass runs before the first
// selected frame of the segment.
#pragma once

#include <string>
#include <vector>

namespace steadylight {

/// One comma-separated part of `--frames`: frames first, first + step, ... up to last (inclusive).
struct FrameSpan {
    int first = 0;
    int last = 0;
    int step = 1;
    std::string text;  // as the user wrote it, for error messages
};

/// The parsed `--frames` option; no spans means every frame of the scene.
struct FrameSelection {
    std::vector<FrameSpan> spans;
};

/// Parses "N", "A-B", "A-B:S" and comma lists of them. Throws InputError naming `--frames` and
/// the bad part for anything else, for B < A, and for a step below 1.
FrameSelection parse_frame_selection(const std::string& text);

/// The selected frames of a scene with `frame_count` frames, sorted and without duplicates.
/// Throws InputError when a span reaches past the scene's last frame.
std::vector<int> select_frames(const FrameSelection& selection, int frame_count);

/// The shortest `--frames` text for sorted `frames`: {0, 1, 2, 5} gives "0-2,5".
std::string format_frame_list(const std::vector<int>& frames);

}  // namespace steadylight
