// Statistics of one rendered frame: counts and wall time per phase, printed after each frame
// and written beside it as JSON (`<scene>_<frame:04>.stats.json`), which `steadylight report`
// reads back. The passes and the path tracer fill them; a method leaves the figures it has no
// part in at zero. timed_phase() is how a pass times one of its phases.
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <string>

#include "steadylight/base/checkpoint.h"
#include "steadylight/base/stopwatch.h"

namespace steadylight {

struct FrameStats {
    std::string method;
    int frame = 0;
    long global_photons_emitted = 0;
    long global_photons_stored = 0;
    long caustic_photons_emitted = 0;
    long caustic_photons_stored = 0;
    long dynamic_photons_stored = 0;       // localized: positive and negative photons of the dynamic map
    long retraced_photon_paths = 0;        // photon paths traced this frame: all, or with reuse those
                                           // that meet a dynamic object (from there on)
    long pixels_reused = 0;                // localized, still camera: pixels taken from the static frame,
    long pixels_looked_up_again = 0;       // their indirect light looked up again, no ray traced,
    long pixels_direct_again = 0;          // only their direct light shaded again,
    long pixels_direct_from_kept = 0;      // (of those, summed from an earlier frame's light samples)
    long pixels_redone_but_direct = 0;     // shaded again without shadow rays,
    long pixels_redone = 0;                // and shaded again whole (all zero: no static frame)
    std::array<long, 4> pixels_changed{};  // pixels whose camera, direct, indirect, caustic term changed
    long irradiance_photons = 0;           // photons whose irradiance was computed (lazily, for gathers)
    long irradiance_reused = 0;            // and taken from the static photons' instead (nothing changed there)
    long irradiance_from_lists = 0;        // of the computed, those whose neighbours came from the static lists
    long irradiance_carried = 0;           // the static ones plus the photons changed around them
    long irradiance_records = 0;           // computed for this frame (localized: the dynamic cache, L_y)
    long static_records = 0;               // localized: records of the segment's static cache
    long fallback_gathers = 0;             // gathers at points the cache did not cover
    long gather_rays = 0;
    double photon_tracing_s = 0;  // tracing the photon maps
    double cache_s = 0;           // building this frame's irradiance cache (localized: L_y), including
                                  // the irradiance at photons its gathers read (photon: all, up front)
    double influence_s = 0;       // localized: the influence I of the dynamic objects
    double correction_s = 0;      // localized: correcting the static records by the dynamic map (L_t)
    double shading_s = 0;         // shading pass: direct light, cache look-ups, specular
    double caustics_s = 0;        // caustic estimates (inside the shading pass, summed over threads)
    double total_s = 0;
    long camera_samples = 0;             // path: pixels x samples per pixel
    long path_rays = 0;                  // path: rays traced, closest-hit and shadow rays
    long path_vertices = 0;              // path: surface hits along the paths (per camera sample: path length)
    double distant_photons_inside = -1;  // photon methods: the share of the photon paths of light from far
                                         // away whose first hit the camera sees (photons/distant_photon_share.h);
                                         // -1: none (left out of the file)
    long non_finite_values = 0;          // channel values of the frame's layers that were NaN or infinite,
                                         // written as 0 (a defect: the tests expect none)
};

void to_json(nlohmann::json& json, const FrameStats& stats);
/// Reads what to_json wrote (`steadylight report`); throws nlohmann::json::exception when a field
/// is missing or has the wrong type. The path tracer's figures came later: a file without them
/// (an older run's) reads them as zero.
void from_json(const nlohmann::json& json, FrameStats& stats);

/// One line for the console: the phases and counts of the frame, each group only when the frame
/// has figures in it (the path tracer's, the photon-mapping passes').
std::string summarize(const FrameStats& stats);

/// Runs `work()` as the frame's phase `name`: a checkpoint (progress, Ctrl-C; base/checkpoint.h),
/// then the work, whose wall time is stored in `seconds` (a FrameStats field). Returns what
/// `work()` returns.
template <class Work>
decltype(auto) timed_phase(std::string_view name, double& seconds, Work&& work) {
    begin_phase(name);
    const Stopwatch time;
    struct Record {  // stores the time also when `work()` returns a value or throws
        const Stopwatch& time;
        double& seconds;
        ~Record() { seconds = time.elapsed_s(); }
    } record{time, seconds};
    return work();
}

}  // namespace steadylight
