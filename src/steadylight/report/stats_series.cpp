#include "steadylight/report/stats_series.h"

#include <algorithm>
#include <map>

#include "steadylight/methods/method.h"

namespace steadylight {
namespace {

/// Where a method sorts among the series of a scene: the reference method first, then the
/// others in the method table's order, then names the table does not know.
int method_rank(const std::string& method) {
    const MethodInfo* info = find_method(method);
    if (!info) return int(methods().size()) + 1;
    if (info->is_reference) return 0;
    return 1 + int(info - methods().data());
}

}  // namespace

std::vector<StatsSeries> group_stats_series(const FrameCatalog& catalog) {
    // The catalog is sorted by scene, then frame, so each series comes out in frame order.
    std::map<std::pair<std::string, std::string>, StatsSeries> grouped;
    for (const CatalogFrame& frame : catalog.frames) {
        if (!frame.stats) continue;
        StatsSeries& series = grouped[{frame.scene, frame.method()}];
        series.scene = frame.scene;
        series.method = frame.method();
        series.frames.push_back(*frame.stats);
    }
    std::vector<StatsSeries> result;
    for (auto& [key, series] : grouped) result.push_back(std::move(series));
    std::stable_sort(result.begin(), result.end(), [](const StatsSeries& a, const StatsSeries& b) {
        if (a.scene != b.scene) return a.scene < b.scene;
        return method_rank(a.method) < method_rank(b.method);
    });
    return result;
}

const std::vector<StatsField>& phase_time_fields() {
    static const std::vector<StatsField> fields{
        {"photon tracing", [](const FrameStats& s) { return s.photon_tracing_s; }},
        {"irradiance cache (L_y)", [](const FrameStats& s) { return s.cache_s; }},
        {"influence", [](const FrameStats& s) { return s.influence_s; }},
        {"L_t correction", [](const FrameStats& s) { return s.correction_s; }},
        {"shading", [](const FrameStats& s) { return s.shading_s; }},
        {"caustics (cpu)", [](const FrameStats& s) { return s.caustics_s; }},
        {"total", [](const FrameStats& s) { return s.total_s; }},
    };
    return fields;
}

const std::vector<StatsField>& count_fields() {
    static const std::vector<StatsField> fields{
        {"irradiance records computed", [](const FrameStats& s) { return double(s.irradiance_records); }},
        {"static records", [](const FrameStats& s) { return double(s.static_records); }},
        {"gather rays", [](const FrameStats& s) { return double(s.gather_rays); }},
        {"fallback gathers", [](const FrameStats& s) { return double(s.fallback_gathers); }},
        {"global photons stored", [](const FrameStats& s) { return double(s.global_photons_stored); }},
        {"caustic photons stored", [](const FrameStats& s) { return double(s.caustic_photons_stored); }},
        {"dynamic photons stored", [](const FrameStats& s) { return double(s.dynamic_photons_stored); }},
        {"photon paths traced", [](const FrameStats& s) { return double(s.retraced_photon_paths); }},
        {"pixels reused", [](const FrameStats& s) { return double(s.pixels_reused); }},
        {"pixels looked up again", [](const FrameStats& s) { return double(s.pixels_looked_up_again); }},
        {"pixels direct again", [](const FrameStats& s) { return double(s.pixels_direct_again); }},
        {"pixels direct from kept samples", [](const FrameStats& s) { return double(s.pixels_direct_from_kept); }},
        {"pixels redone but direct", [](const FrameStats& s) { return double(s.pixels_redone_but_direct); }},
        {"pixels redone", [](const FrameStats& s) { return double(s.pixels_redone); }},
        {"pixels with camera rays changed", [](const FrameStats& s) { return double(s.pixels_changed[0]); }},
        {"pixels with direct light changed", [](const FrameStats& s) { return double(s.pixels_changed[1]); }},
        {"pixels with indirect light changed", [](const FrameStats& s) { return double(s.pixels_changed[2]); }},
        {"pixels with caustics changed", [](const FrameStats& s) { return double(s.pixels_changed[3]); }},
        {"camera samples (path)", [](const FrameStats& s) { return double(s.camera_samples); }},
        {"rays traced (path)", [](const FrameStats& s) { return double(s.path_rays); }},
        {"path length (vertices a sample)",
         [](const FrameStats& s) {
             return s.camera_samples > 0 ? double(s.path_vertices) / double(s.camera_samples) : 0.0;
         }},
    };
    return fields;
}

double mean_of(const StatsSeries& series, const StatsField& field) {
    if (series.frames.empty()) return 0;
    double sum = 0;
    for (const FrameStats& stats : series.frames) sum += field.value(stats);
    return sum / double(series.frames.size());
}

}  // namespace steadylight
