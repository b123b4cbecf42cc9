// Line plots as inline SVG for `steadylight report`: axes with "nice" ticks (1, 2 or 5 times a
// power of ten), axis labels, one polyline per series and a legend. No scripts, no fonts to
// fetch: the SVG goes straight into the HTML page.
#pragma once

#include <string>
#include <vector>

namespace steadylight {

/// One line: points (x[i], y[i]); non-finite points are left out.
struct PlotSeries {
    std::string name;
    std::vector<double> x, y;
};

struct LinePlot {
    std::string title;
    std::string x_label, y_label;
    std::vector<PlotSeries> series;
    bool integer_x = true;  // x ticks on whole numbers only (frames)
    int width_px = 760, height_px = 300;
};

/// \brief An `<svg>` element drawing the series over a shared x and y axis.
/// The y axis starts at 0 unless a value is negative and ends at the first tick above the
/// largest value. Each series becomes `<polyline class="series" data-series="NAME" points=...>`
/// with one "x,y" pair per finite point.
std::string build_svg_line_plot(const LinePlot& plot);

/// Tick values covering [lo, hi] outwards, at a step of 1, 2 or 5 times a power of ten that
/// gives at most about `max_count` intervals and is at least `min_step`.
std::vector<double> nice_ticks(double lo, double hi, int max_count, double min_step = 0);

/// A tick label with as many decimals as `step` needs, large values as "12k" or "2.5M".
std::string format_tick(double value, double step);

}  // namespace steadylight
