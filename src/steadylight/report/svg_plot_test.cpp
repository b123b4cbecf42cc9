// Tests of the SVG line plots of `steadylight report`, on hand-made data.
#include "steadylight/report/svg_plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <regex>

namespace steadylight {
namespace {

/// The "x,y" pairs of every polyline in `svg`, one vector per polyline.
std::vector<std::vector<std::pair<double, double>>> polylines(const std::string& svg) {
    static const std::regex polyline(R"re(<polyline[^>]* points="([^"]*)")re");
    static const std::regex pair(R"(([-\d.]+),([-\d.]+))");
    std::vector<std::vector<std::pair<double, double>>> result;
    for (std::sregex_iterator it(svg.begin(), svg.end(), polyline), end; it != end; ++it) {
        const std::string points = (*it)[1];
        auto& line = result.emplace_back();
        for (std::sregex_iterator p(points.begin(), points.end(), pair); p != end; ++p)
            line.emplace_back(std::stod((*p)[1]), std::stod((*p)[2]));
    }
    return result;
}

LinePlot two_series_plot() {
    return {"time per frame",
            "frame",
            "seconds",
            {{"photon", {0, 1, 2, 3, 4}, {3.7, 3.8, 3.6, 3.9, 3.75}},
             {"localized", {0, 1, 2, 3, 4}, {2.7, 2.6, 2.8, 2.7, 2.65}}}};
}

TEST(SvgPlot, NiceTicksStepByOneTwoOrFive) {
    EXPECT_EQ(nice_ticks(0, 9.3, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
    const std::vector<double> fine = nice_ticks(0, 0.9, 5);
    ASSERT_EQ(fine.size(), 6u);
    for (size_t i = 0; i < fine.size(); ++i) EXPECT_NEAR(fine[i], 0.2 * double(i), 1e-12);
    EXPECT_EQ(nice_ticks(0, 2, 10, 1), (std::vector<double>{0, 1, 2}));
}

TEST(SvgPlot, TickLabelsHaveTheDecimalsTheStepNeeds) {
    EXPECT_EQ(format_tick(0.05, 0.05), "0.05");
    EXPECT_EQ(format_tick(1.5, 0.5), "1.5");
    EXPECT_EQ(format_tick(40, 20), "40");
    EXPECT_EQ(format_tick(15000, 5000), "15k");
    EXPECT_EQ(format_tick(2'500'000, 500'000), "2500k");
    EXPECT_EQ(format_tick(3'000'000, 1'000'000), "3M");
    EXPECT_EQ(format_tick(1e-17, 0.1), "0");
}

TEST(SvgPlot, EmptyPlotIsAnSvgWithoutLines) {
    const std::string svg = build_svg_line_plot({"nothing", "frame", "seconds", {}});
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    EXPECT_TRUE(polylines(svg).empty());
}

TEST(SvgPlot, EachSeriesIsAPolylineWithOnePointPerValue) {
    const std::string svg = build_svg_line_plot(two_series_plot());
    const auto lines = polylines(svg);
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[0].size(), 5u);
    EXPECT_EQ(lines[1].size(), 5u);
    EXPECT_NE(svg.find(R"(data-series="photon")"), std::string::npos);
    EXPECT_NE(svg.find(">localized</text>"), std::string::npos);  // the legend
    EXPECT_NE(svg.find(">seconds</text>"), std::string::npos);    // the y label
}

TEST(SvgPlot, PointsLieInsideThePictureAndFollowTheData) {
    const LinePlot plot = two_series_plot();
    const auto lines = polylines(build_svg_line_plot(plot));
    for (const auto& line : lines)
        for (const auto& [x, y] : line) {
            EXPECT_GT(x, 0);
            EXPECT_LT(x, plot.width_px);
            EXPECT_GT(y, 0);
            EXPECT_LT(y, plot.height_px);
        }
    // Larger values are higher up (smaller y); later frames further right.
    EXPECT_LT(lines[0][3].second, lines[0][2].second);
    EXPECT_LT(lines[0][0].second, lines[1][0].second);
    EXPECT_LT(lines[0][0].first, lines[0][1].first);
}

TEST(SvgPlot, NonFinitePointsAreLeftOut) {
    const std::string svg = build_svg_line_plot({"t", "x", "y", {{"a", {0, 1, 2}, {1, std::nan(""), 2}}}});
    ASSERT_EQ(polylines(svg).size(), 1u);
    EXPECT_EQ(polylines(svg)[0].size(), 2u);
}

TEST(SvgPlot, ASinglePointStillGetsAnAxis) {
    const std::string svg = build_svg_line_plot({"t", "frame", "s", {{"a", {7}, {0}}}});
    ASSERT_EQ(polylines(svg).size(), 1u);
    EXPECT_EQ(polylines(svg)[0].size(), 1u);
    EXPECT_NE(svg.find(">7</text>"), std::string::npos);
}

TEST(SvgPlot, TextIsEscaped) {
    const std::string svg = build_svg_line_plot({"a<b", "x", "y", {{"c&d", {0}, {1}}}});
    EXPECT_NE(svg.find("a&lt;b"), std::string::npos);
    EXPECT_NE(svg.find("c&amp;d"), std::string::npos);
    EXPECT_EQ(svg.find("a<b"), std::string::npos);
}

}  // namespace
}  // namespace steadylight
