#include "steadylight/report/report_tables.h"

#include <fmt/format.h>

#include <cmath>

#include "steadylight/methods/method.h"
#include "steadylight/report/html.h"

namespace steadylight {
namespace {

std::string format_number(double value) {
    if (value == 0) return "0";
    if (std::abs(value) < 10) return fmt::format("{:.3f}", value);
    return fmt::format("{:.1f}", value);
}

/// A ratio where both sides have something to compare (a phase one method lacks has none).
std::string format_ratio(double numerator, double denominator) {
    if (numerator == 0 || denominator == 0 || !std::isfinite(numerator / denominator)) return "&mdash;";
    return fmt::format("{:.2f}x", numerator / denominator);
}

/// The series of one scene, the reference method's (photon) first when it is there.
struct SceneSeries {
    std::string scene;
    std::vector<const StatsSeries*> series;
    const StatsSeries* reference = nullptr;
};

std::vector<SceneSeries> split_by_scene(const std::vector<StatsSeries>& all) {
    std::vector<SceneSeries> scenes;
    for (const StatsSeries& series : all) {
        if (scenes.empty() || scenes.back().scene != series.scene) scenes.push_back({series.scene, {}, nullptr});
        scenes.back().series.push_back(&series);
        const MethodInfo* method = find_method(series.method);
        if (method && method->is_reference) scenes.back().reference = &series;
    }
    return scenes;
}

std::string header_row(const SceneSeries& scene) {
    std::string row = "<tr><th>per frame (means)</th>";
    for (const StatsSeries* series : scene.series) row += "<th>" + escape_html(series->method) + "</th>";
    for (const StatsSeries* series : scene.series)
        if (scene.reference && series != scene.reference)
            row += "<th>" + escape_html(scene.reference->method) + " / " + escape_html(series->method) + "</th>";
    return row + "</tr>\n";
}

std::string field_row(const SceneSeries& scene, const std::string& label, const StatsField& field) {
    std::string row = "<tr><th>" + escape_html(label) + "</th>";
    for (const StatsSeries* series : scene.series) row += "<td>" + format_number(mean_of(*series, field)) + "</td>";
    for (const StatsSeries* series : scene.series)
        if (scene.reference && series != scene.reference)
            row += "<td>" + format_ratio(mean_of(*scene.reference, field), mean_of(*series, field)) + "</td>";
    return row + "</tr>\n";
}

std::string frames_row(const SceneSeries& scene) {
    std::string row = "<tr><th>frames</th>";
    for (const StatsSeries* series : scene.series) row += fmt::format("<td>{}</td>", series->frames.size());
    for (const StatsSeries* series : scene.series)
        if (scene.reference && series != scene.reference) row += "<td></td>";
    return row + "</tr>\n";
}

std::string scene_table(const SceneSeries& scene) {
    std::string html = "<table class=\"summary\" data-scene=\"" + escape_html(scene.scene) + "\">\n<caption>" +
                       escape_html(scene.scene) + "</caption>\n" + header_row(scene) + frames_row(scene);
    for (const StatsField& field : phase_time_fields())
        html += field_row(scene, field.label + std::string(" (s)"), field);
    for (const StatsField& field : count_fields()) html += field_row(scene, field.label, field);
    return html + "</table>\n";
}

}  // namespace

std::string build_summary_tables_html(const std::vector<StatsSeries>& series) {
    std::string html;
    for (const SceneSeries& scene : split_by_scene(series)) html += scene_table(scene);
    return html;
}

}  // namespace steadylight
