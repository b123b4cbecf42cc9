// The per-frame statistics of an output folder as series for plots and tables: one series per
// scene and method (the method each frame's stats.json names), and the fields a report shows.
#pragma once

#include <string>
#include <vector>

#include "steadylight/passes/frame_stats.h"
#include "steadylight/report/frame_catalog.h"

namespace steadylight {

/// The statistics of the frames of one scene rendered with one method, in frame order.
struct StatsSeries {
    std::string scene;
    std::string method;
    std::vector<FrameStats> frames;
};

/// One series per (scene, method) pair with statistics; methods of a scene in the order photon,
/// localized, frozen, then any other alphabetically. Frames without statistics are left out.
std::vector<StatsSeries> group_stats_series(const FrameCatalog& catalog);

/// A number read from a frame's statistics, with the words that describe it.
struct StatsField {
    const char* label;
    double (*value)(const FrameStats&);
};

/// The wall time of each phase and the total, in seconds (caustics is cpu time summed over
/// threads, already inside shading).
const std::vector<StatsField>& phase_time_fields();
/// Counts: records computed, static records, gather rays, photons stored, fallback gathers; the
/// path tracer's camera samples, rays traced and mean path length.
const std::vector<StatsField>& count_fields();

/// Mean of `field` over the frames of `series`.
double mean_of(const StatsSeries& series, const StatsField& field);

}  // namespace steadylight
