// `steadylight report OUTDIR`: one self-contained HTML page about a rendered animation: summary
// tables, plots of the per-frame statistics (inline SVG), a contact sheet of the frames and the
// AOV layers of one frame. Images are embedded as data URIs and nothing is fetched from the
// network, so the page can be mailed or archived on its own.
#pragma once

#include <optional>
#include <string>

namespace steadylight {

struct ReportSettings {
    std::string out_dir;       // the folder `steadylight render --out` wrote
    std::optional<int> frame;  // frame whose AOVs are shown; default: each scene's middle frame
    std::string html_file;     // default: <out_dir>/report.html
};

/// \brief The HTML page for the frames in `settings.out_dir`.
/// Throws InputError when the folder is missing or holds no frame, when a statistics file, PNG
/// or EXR cannot be read (naming it), and when `settings.frame` is no frame of the folder.
std::string build_report_html(const ReportSettings& settings);

/// Builds the page and writes it atomically; returns the path written.
std::string write_report(const ReportSettings& settings);

}  // namespace steadylight
