#include "steadylight/report/svg_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "steadylight/report/html.h"

namespace steadylight {
namespace {

constexpr const char* palette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                   "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
constexpr double margin_left = 64, margin_top = 30, margin_bottom = 44, legend_width = 190;

struct Range {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -std::numeric_limits<double>::infinity();

    void include(double v) { lo = std::min(lo, v), hi = std::max(hi, v); }
    bool empty() const { return !(lo <= hi); }
};

/// The plot's rectangle in pixels and the data range it shows.
struct PlotArea {
    double left, top, right, bottom;
    Range x, y;

    double px(double v) const { return left + (v - x.lo) / (x.hi - x.lo) * (right - left); }
    double py(double v) const { return bottom - (v - y.lo) / (y.hi - y.lo) * (bottom - top); }
};

bool finite_point(const PlotSeries& series, size_t i) {
    return i < series.y.size() && std::isfinite(series.x[i]) && std::isfinite(series.y[i]);
}

/// The data range over every finite point, widened so that neither axis is empty; y from 0.
PlotArea fit_area(const LinePlot& plot, std::vector<double>& x_ticks, std::vector<double>& y_ticks) {
    PlotArea area{margin_left, margin_top, plot.width_px - legend_width, plot.height_px - margin_bottom, {}, {}};
    area.y.include(0);
    for (const PlotSeries& series : plot.series)
        for (size_t i = 0; i < series.x.size(); ++i)
            if (finite_point(series, i)) area.x.include(series.x[i]), area.y.include(series.y[i]);
    if (area.x.empty()) area.x = {0, 1};
    if (area.x.hi == area.x.lo) area.x = {area.x.lo - 1, area.x.hi + 1};
    if (area.y.hi == area.y.lo) area.y.hi = area.y.lo + 1;
    // The y axis ends on ticks; the x axis keeps the data's ends and shows the ticks inside.
    y_ticks = nice_ticks(area.y.lo, area.y.hi, 5);
    area.y = {y_ticks.front(), y_ticks.back()};
    for (const double tick : nice_ticks(area.x.lo, area.x.hi, 10, plot.integer_x ? 1 : 0))
        if (tick >= area.x.lo - 1e-9 && tick <= area.x.hi + 1e-9) x_ticks.push_back(tick);
    return area;
}

std::string draw_axes(const LinePlot& plot, const PlotArea& area, const std::vector<double>& x_ticks,
                      const std::vector<double>& y_ticks) {
    std::string svg;
    const double y_step = y_ticks.size() > 1 ? y_ticks[1] - y_ticks[0] : 1;
    for (const double tick : y_ticks)
        svg += fmt::format(R"(<line x1="{0:.1f}" x2="{1:.1f}" y1="{2:.1f}" y2="{2:.1f}" stroke="#ddd"/>)"
                           R"(<text x="{3:.1f}" y="{4:.1f}" text-anchor="end">{5}</text>)",
                           area.left, area.right, area.py(tick), area.left - 6, area.py(tick) + 4,
                           format_tick(tick, y_step));
    const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : 1;
    for (const double tick : x_ticks)
        svg += fmt::format(R"(<line x1="{0:.1f}" x2="{0:.1f}" y1="{1:.1f}" y2="{2:.1f}" stroke="#333"/>)"
                           R"(<text x="{0:.1f}" y="{3:.1f}" text-anchor="middle">{4}</text>)",
                           area.px(tick), area.bottom, area.bottom + 5, area.bottom + 18, format_tick(tick, x_step));
    svg += fmt::format(R"(<path d="M{0:.1f},{1:.1f}V{2:.1f}H{3:.1f}" fill="none" stroke="#333"/>)", area.left, area.top,
                       area.bottom, area.right);
    svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle">{}</text>)", (area.left + area.right) / 2,
                       area.bottom + 36, escape_html(plot.x_label));
    svg += fmt::format(R"svg(<text transform="translate(14,{:.1f}) rotate(-90)" text-anchor="middle">{}</text>)svg",
                       (area.top + area.bottom) / 2, escape_html(plot.y_label));
    return svg;
}

std::string draw_series(const PlotSeries& series, const PlotArea& area, const char* colour) {
    std::string points, markers;
    for (size_t i = 0; i < series.x.size(); ++i) {
        if (!finite_point(series, i)) continue;
        const double x = area.px(series.x[i]), y = area.py(series.y[i]);
        points += fmt::format("{}{:.1f},{:.1f}", points.empty() ? "" : " ", x, y);
        markers += fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="2.5"/>)", x, y);
    }
    return fmt::format(R"(<polyline class="series" data-series="{0}" fill="none" stroke="{1}" stroke-width="1.5" )"
                       R"(points="{2}"/><g fill="{1}">{3}</g>)",
                       escape_html(series.name), colour, points, markers);
}

std::string draw_legend(const LinePlot& plot, const PlotArea& area) {
    std::string svg;
    for (size_t i = 0; i < plot.series.size(); ++i) {
        const double y = area.top + 8 + 18 * double(i), x = area.right + 16;
        svg += fmt::format(R"(<line x1="{:.1f}" x2="{:.1f}" y1="{:.1f}" y2="{:.1f}" stroke="{}" stroke-width="3"/>)"
                           R"(<text x="{:.1f}" y="{:.1f}">{}</text>)",
                           x, x + 18, y, y, palette[i % std::size(palette)], x + 24, y + 4,
                           escape_html(plot.series[i].name));
    }
    return svg;
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int max_count, double min_step) {
    const double raw_step = std::max((hi - lo) / std::max(1, max_count), 1e-300);
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw_step)));
    const double normalized = raw_step / magnitude;
    double step = (normalized <= 1 ? 1 : normalized <= 2 ? 2 : normalized <= 5 ? 5 : 10) * magnitude;
    step = std::max(step, min_step);
    std::vector<double> ticks;
    const double first = std::floor(lo / step + 1e-9), last = std::ceil(hi / step - 1e-9);
    for (double k = first; k <= last; ++k) ticks.push_back(k * step);
    if (ticks.size() < 2) ticks.push_back(ticks.empty() ? lo : ticks.back() + step);
    return ticks;
}

std::string format_tick(double value, double step) {
    if (std::abs(value) < 1e-9 * std::max(1.0, std::abs(step))) return "0";
    const auto decimals = [](double s) { return std::max(0, int(std::ceil(-std::log10(s) - 1e-9))); };
    if (step >= 1e6) return fmt::format("{:.{}f}M", value / 1e6, decimals(step / 1e6));
    if (step >= 1e3) return fmt::format("{:.{}f}k", value / 1e3, decimals(step / 1e3));
    return fmt::format("{:.{}f}", value, decimals(step));
}

std::string build_svg_line_plot(const LinePlot& plot) {
    std::vector<double> x_ticks, y_ticks;
    const PlotArea area = fit_area(plot, x_ticks, y_ticks);
    std::string svg = fmt::format(
        R"(<svg xmlns="http://www.w3.org/2000/svg" class="plot" width="{0}" height="{1}" viewBox="0 0 {0} {1}" )"
        R"(font-family="sans-serif" font-size="11" role="img" aria-label="{2}"><title>{2}</title>)"
        R"(<text x="{3:.1f}" y="16" font-size="13" font-weight="bold">{2}</text>)",
        plot.width_px, plot.height_px, escape_html(plot.title), area.left);
    svg += draw_axes(plot, area, x_ticks, y_ticks);
    for (size_t i = 0; i < plot.series.size(); ++i)
        svg += draw_series(plot.series[i], area, palette[i % std::size(palette)]);
    svg += draw_legend(plot, area);
    return svg + "</svg>";
}

}  // namespace steadylight
