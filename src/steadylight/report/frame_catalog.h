// What a render left in an output folder, as `steadylight report` finds it: the frames
// `<scene>_<frame:04>.{exr,png,stats.json}` of every scene, and each frame's statistics. The
// method of a frame is the one its stats.json names, never guessed from file names.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "steadylight/passes/frame_stats.h"

namespace steadylight {

/// One frame of one scene; a file that is absent has an empty name.
struct CatalogFrame {
    std::string scene;
    int frame = 0;
    std::string exr_file, png_file, stats_file;
    std::optional<FrameStats> stats;  // absent without a stats.json (path frames of older runs)

    /// The method named by the statistics, or "" when there are none.
    std::string method() const { return stats ? stats->method : ""; }
};

/// The frames of an output folder, sorted by scene, then frame.
struct FrameCatalog {
    std::string out_dir;
    std::vector<CatalogFrame> frames;

    /// The scene names, sorted.
    std::vector<std::string> scenes() const;
    /// The frames of one scene, in frame order.
    std::vector<CatalogFrame> frames_of(const std::string& scene) const;
};

/// \brief Finds the frames in `out_dir` and reads their statistics.
/// Throws InputError when the folder is missing or holds no frame, or naming the stats.json that
/// cannot be parsed. Other files (AOV PNGs, caches, settings, the report itself) are ignored.
FrameCatalog load_frame_catalog(const std::string& out_dir);

}  // namespace steadylight
