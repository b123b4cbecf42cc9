// Parsing `--frames` and expanding it against the scene (frame_selection.h).
#include "steadylight/run/frame_selection.h"

#include <algorithm>
#include <regex>

#include <fmt/format.h>

#include "steadylight/base/error.h"

namespace steadylight {
namespace {

constexpr const char* syntax = "expected N, A-B or A-B:STEP, or a comma list of them (\"1,5,10-20:5\")";

std::string trimmed(const std::string& text) {
    const size_t begin = text.find_first_not_of(" \t");
    if (begin == std::string::npos) return "";
    return text.substr(begin, text.find_last_not_of(" \t") - begin + 1);
}

FrameSpan parse_frame_span(const std::string& part) {
    // Up to 9 digits, so that every number fits an int.
    static const std::regex pattern(R"((\d{1,9})(?:\s*-\s*(\d{1,9})(?:\s*:\s*(\d{1,9}))?)?)");
    const std::string text = trimmed(part);
    std::smatch match;
    if (!std::regex_match(text, match, pattern)) throw InputError("--frames", fmt::format("\"{}\": {}", text, syntax));
    FrameSpan span{std::stoi(match[1]), 0, 1, text};
    span.last = match[2].matched ? std::stoi(match[2]) : span.first;
    if (match[3].matched) span.step = std::stoi(match[3]);
    if (span.last < span.first)
        throw InputError("--frames", fmt::format("\"{}\": the range ends before it starts", text));
    if (span.step < 1) throw InputError("--frames", fmt::format("\"{}\": the step must be at least 1", text));
    return span;
}

}  // namespace

FrameSelection parse_frame_selection(const std::string& text) {
    FrameSelection selection;
    size_t begin = 0;
    while (true) {
        const size_t comma = text.find(',', begin);
        selection.spans.push_back(parse_frame_span(text.substr(begin, comma - begin)));
        if (comma == std::string::npos) return selection;
        begin = comma + 1;
    }
}

std::vector<int> select_frames(const FrameSelection& selection, int frame_count) {
    if (selection.spans.empty()) {
        std::vector<int> all(size_t(std::max(frame_count, 0)));
        for (size_t i = 0; i < all.size(); ++i) all[i] = int(i);
        return all;
    }
    std::vector<int> frames;
    for (const FrameSpan& span : selection.spans) {
        if (span.last >= frame_count)
            throw InputError("--frames", fmt::format("frame {} is past the scene's last frame {} (in \"{}\")",
                                                     span.last, frame_count - 1, span.text));
        for (long frame = span.first; frame <= span.last; frame += span.step) frames.push_back(int(frame));
    }
    std::sort(frames.begin(), frames.end());
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
    return frames;
}

std::string format_frame_list(const std::vector<int>& frames) {
    std::string text;
    for (size_t i = 0; i < frames.size();) {
        size_t j = i;
        while (j + 1 < frames.size() && frames[j + 1] == frames[j] + 1) ++j;
        if (!text.empty()) text += ",";
        text += j == i ? fmt::format("{}", frames[i]) : fmt::format("{}-{}", frames[i], frames[j]);
        i = j + 1;
    }
    return text;
}

}  // namespace steadylight
