// What a farm submission asks for (`steadylight submit`, docs/farm.md): per segment of the
// animation, a bake job when its static cache file is not valid yet, and the segment's frames
// that are not complete, in chunks of at most N frames that never span two segments; then one
// finishing job. Frames complete from earlier runs and valid cache files are left alone, so
// submitting again resumes.
#pragma once

#include <string>
#include <vector>

#include "steadylight/scene/scene.h"

namespace steadylight {

/// One segment's jobs.
struct SegmentJobs {
    int segment = 0;                  // index into Scene::segments()
    Segment frames;                   // the segment's frames
    std::string cache_file;           // its static cache file ("" when the method has no static pass)
    bool bake = false;                // the cache file is missing or not valid: a bake job first
    std::vector<std::string> chunks;  // `--frames` texts, one per array task
};

struct JobPlan {
    std::vector<SegmentJobs> segments;  // only segments with frames to render
    std::vector<int> selected;          // every selected frame (the finishing job checks them)
    std::vector<int> missing;           // the selected frames not complete yet
};

/// \brief `frames` (sorted) cut into runs of at most `chunk_frames` frames, each as a `--frames`
/// text: {0, 1, 2, 3, 5} in chunks of 2 gives "0-1", "2-3", "5".
std::vector<std::string> chunk_frame_lists(const std::vector<int>& frames, int chunk_frames);

}  // namespace steadylight
