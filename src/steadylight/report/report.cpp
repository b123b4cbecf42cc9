#include "steadylight/report/report.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "steadylight/base/atomic_file.h"
#include "steadylight/base/error.h"
#include "steadylight/report/frame_catalog.h"
#include "steadylight/report/html.h"
#include "steadylight/report/report_images.h"
#include "steadylight/report/report_tables.h"
#include "steadylight/report/stats_series.h"
#include "steadylight/report/svg_plot.h"

namespace steadylight {
namespace {

constexpr const char* page_style = R"(
body { font-family: sans-serif; margin: 1.5em; color: #222; background: #fff; }
h1 { font-size: 1.4em; } h2 { margin-top: 1.6em; border-bottom: 1px solid #ccc; } h3 { margin-bottom: .4em; }
table { border-collapse: collapse; margin: .6em 0 1.2em; font-size: .9em; }
th, td { border: 1px solid #ccc; padding: .2em .6em; } td { text-align: right; font-variant-numeric: tabular-nums; }
th { background: #f4f4f4; text-align: left; } caption { font-weight: bold; text-align: left; padding: .2em 0; }
.plots { display: flex; flex-wrap: wrap; gap: 1em; }
.sheet, .aovs { display: flex; flex-wrap: wrap; gap: .6em; }
figure { margin: 0; font-size: .8em; text-align: center; }
.frame img { width: 160px; display: block; image-rendering: auto; }
.aov img { max-width: 320px; min-width: 160px; display: block; }
.missing { width: 160px; height: 90px; background: #eee; line-height: 90px; }
)";

// Reports, once the page has loaded, how many images decoded: scripts/check_report.sh reads it
// from the DOM that headless Chromium dumps. The page needs no script otherwise.
constexpr const char* decode_check_script = R"(<script>
addEventListener('load', () => {
  const images = Array.from(document.images);
  document.body.dataset.imagesDecoded = images.filter(i => i.complete && i.naturalWidth > 0).length + '/' + images.length;
});
</script>)";

std::string series_name(const StatsSeries& series, bool several_scenes) {
    return several_scenes ? series.scene + " \u00b7 " + series.method : series.method;
}

PlotSeries plot_series(const StatsSeries& series, const std::string& name, const StatsField& field) {
    PlotSeries plotted{name, {}, {}};
    for (const FrameStats& stats : series.frames) {
        plotted.x.push_back(stats.frame);
        plotted.y.push_back(field.value(stats));
    }
    return plotted;
}

/// One plot of `field` with a line per series.
std::string method_comparison_plot(const std::vector<StatsSeries>& all, const std::string& title,
                                   const std::string& y_label, const StatsField& field, bool several_scenes) {
    LinePlot plot{title, "frame", y_label, {}};
    for (const StatsSeries& series : all)
        plot.series.push_back(plot_series(series, series_name(series, several_scenes), field));
    return build_svg_line_plot(plot);
}

/// `fields` of one series, one line each; fields that are zero in every frame are left out, and
/// the plot too when all are.
std::string fields_plot(const StatsSeries& series, const std::string& title, const std::string& y_label,
                        const std::vector<const StatsField*>& fields) {
    LinePlot plot{title, "frame", y_label, {}};
    for (const StatsField* field : fields)
        if (std::any_of(series.frames.begin(), series.frames.end(),
                        [&](const FrameStats& s) { return field->value(s) > 0; }))
            plot.series.push_back(plot_series(series, field->label, *field));
    return plot.series.empty() ? "" : build_svg_line_plot(plot) + "\n";
}

/// The phases of one series, one line each; phases that took no time in any frame are left out.
std::string phase_plot(const StatsSeries& series, bool several_scenes) {
    std::vector<const StatsField*> fields;
    for (const StatsField& field : phase_time_fields()) fields.push_back(&field);
    return fields_plot(series, "time per phase: " + series_name(series, several_scenes), "seconds", fields);
}

/// What a series' frames did anew and what they reused (docs/localized.md, "Pixels reused"):
/// the pixels per kind of work, and those whose camera, direct, indirect, caustic term changed.
std::string reuse_plot(const StatsSeries& series, bool several_scenes) {
    std::vector<const StatsField*> fields;
    for (const StatsField& field : count_fields())
        if (std::string_view(field.label).starts_with("pixels")) fields.push_back(&field);
    return fields_plot(series, "pixels per frame: " + series_name(series, several_scenes), "pixels", fields);
}

std::string plots_html(const std::vector<StatsSeries>& all) {
    if (all.empty()) return "<p>No frame statistics (no stats.json beside the frames).</p>\n";
    const bool several_scenes = all.front().scene != all.back().scene;
    const StatsField& total = phase_time_fields().back();
    const StatsField& records = count_fields().front();
    std::string html = "<div class=\"plots\">\n";
    html += method_comparison_plot(all, "time per frame", "seconds", total, several_scenes) + "\n";
    html +=
        method_comparison_plot(all, "irradiance records computed per frame", "records", records, several_scenes) + "\n";
    const auto paths = std::find_if(count_fields().begin(), count_fields().end(), [](const StatsField& field) {
        return std::string_view(field.label) == "photon paths traced";
    });
    html += method_comparison_plot(all, "photon paths traced per frame", "paths", *paths, several_scenes) + "\n";
    for (const StatsSeries& series : all)
        html += phase_plot(series, several_scenes) + reuse_plot(series, several_scenes);
    return html + "</div>\n";
}

std::string overview_html(const FrameCatalog& catalog) {
    std::string html =
        "<table class=\"overview\">\n<tr><th>scene</th><th>frames</th><th>first</th><th>last</th>"
        "<th>methods</th><th>without statistics</th><th>total time (s)</th></tr>\n";
    for (const std::string& scene : catalog.scenes()) {
        const std::vector<CatalogFrame> frames = catalog.frames_of(scene);
        std::vector<std::string> methods;
        int without_stats = 0;
        double total_s = 0;
        for (const CatalogFrame& frame : frames) {
            if (!frame.stats)
                ++without_stats;
            else
                total_s += frame.stats->total_s;
            if (frame.stats && std::find(methods.begin(), methods.end(), frame.method()) == methods.end())
                methods.push_back(frame.method());
        }
        std::string method_list;
        for (const std::string& method : methods)
            method_list += (method_list.empty() ? "" : ", ") + escape_html(method);
        html +=
            fmt::format("<tr><th>{}</th><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{:.2f}</td></tr>\n",
                        escape_html(scene), frames.size(), frames.front().frame, frames.back().frame, method_list,
                        without_stats, total_s);
    }
    return html + "</table>\n";
}

void check_requested_frame(const FrameCatalog& catalog, std::optional<int> frame) {
    if (!frame) return;
    const bool found = std::any_of(catalog.frames.begin(), catalog.frames.end(),
                                   [&](const CatalogFrame& f) { return f.frame == *frame && !f.exr_file.empty(); });
    if (!found) throw InputError("--frame", fmt::format("no EXR of frame {} in {}", *frame, catalog.out_dir));
}

}  // namespace

std::string build_report_html(const ReportSettings& settings) {
    const FrameCatalog catalog = load_frame_catalog(settings.out_dir);
    check_requested_frame(catalog, settings.frame);
    const std::vector<StatsSeries> series = group_stats_series(catalog);
    const std::string title = "steadylight report: " + escape_html(settings.out_dir);
    std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + title +
                       "</title>\n<style>" + page_style + "</style>\n</head>\n<body>\n<h1>" + title + "</h1>\n";
    html += fmt::format("<p>{} frame(s); steadylight {}.</p>\n", catalog.frames.size(), STEADYLIGHT_VERSION);
    html += "<h2 id=\"summary\">Summary</h2>\n" + overview_html(catalog) + build_summary_tables_html(series);
    html += "<h2 id=\"plots\">Per-frame statistics</h2>\n" + plots_html(series);
    html += "<h2 id=\"frames\">Frames</h2>\n" + build_contact_sheet_html(catalog);
    html += "<h2 id=\"aovs\">AOV layers</h2>\n" + build_aov_html(catalog, settings.frame);
    return html + decode_check_script + "\n</body>\n</html>\n";
}

std::string write_report(const ReportSettings& settings) {
    const std::string path = settings.html_file.empty()
                                 ? (std::filesystem::path(settings.out_dir) / "report.html").string()
                                 : settings.html_file;
    const std::string html = build_report_html(settings);
    try {
        write_text_file(path, html);
    } catch (const std::runtime_error& e) {
        throw InputError("", e.what());  // an unwritable --out is the user's to fix
    }
    return path;
}

}  // namespace steadylight
