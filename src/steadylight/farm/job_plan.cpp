// Cutting a segment's frames into chunks (job_plan.h).
#include "steadylight/farm/job_plan.h"

#include "steadylight/run/frame_selection.h"

namespace steadylight {

std::vector<std::string> chunk_frame_lists(const std::vector<int>& frames, int chunk_frames) {
    std::vector<std::string> chunks;
    for (size_t start = 0; start < frames.size(); start += size_t(chunk_frames)) {
        const size_t end = std::min(frames.size(), start + size_t(chunk_frames));
        chunks.push_back(format_frame_list(std::vector<int>(frames.begin() + long(start), frames.begin() + long(end))));
    }
    return chunks;
}

}  // namespace steadylight
