// The SVG plots' parts for a study's summary plots: logarithmic axes (ticks, positions, points they cannot show),
// ticks of the caller's choosing with labels (categories), error bars, marker shapes and dash patterns that tell
// series apart, and bands over part of the x range.

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "markup_support.h"
#include "swa/monitor/svg_plot.h"

namespace swa::monitor {
namespace {

using testing::attr;
using testing::elements;
using testing::num;
using testing::occurrences;
using testing::texts;

PlotSeries markerSeries(std::vector<double> x, std::vector<double> y, MarkerShape shape = MarkerShape::kDot) {
  PlotSeries s;
  s.x = std::move(x);
  s.y = std::move(y);
  s.marker = shape;
  return s;
}

TEST(LogTicks, PowersOfTenWhenThreeFitElseOneTwoFiveElseOneToNine) {
  EXPECT_EQ(logTicks(0.001, 1.0).values, (std::vector<double>{0.001, 0.01, 0.1, 1.0}));
  EXPECT_EQ(logTicks(0.02, 0.2).values, (std::vector<double>{0.02, 0.05, 0.1, 0.2}));
  const AxisTicks narrow = logTicks(0.041, 0.06);
  EXPECT_TRUE(narrow.log);
  EXPECT_GE(narrow.values.size(), 2u) << "a factor 1.5 still gets two ticks";
  for (const double v : narrow.values) EXPECT_TRUE(v >= narrow.lo && v <= narrow.hi) << v;
  EXPECT_GE(narrow.hi / narrow.lo, 3.0) << "at least a factor 3 shown";
  // Labels carry the decimals of their own power of ten.
  EXPECT_EQ(formatTick(0.05, narrow), "0.05");
  EXPECT_EQ(formatTick(20.0, logTicks(4.0, 32.0)), "20");
  // Many decades keep at most 2 × target ticks.
  EXPECT_LE(logTicks(1e-12, 1e12, 6).values.size(), 12u);
  // Nothing positive: a decade, not a crash.
  const AxisTicks none = logTicks(-1.0, 0.0);
  EXPECT_GT(none.lo, 0.0);
  EXPECT_FALSE(none.values.empty());
}

TEST(SvgPlot, LogAxesPlaceDecadesEvenlyAndDropAndCountWhatTheyCannotShow) {
  // GIVEN y = 1/sqrt(x) for x = 1, 4, 16, 64, and one point with y = 0
  PlotSpec spec;
  spec.x_log = true;
  spec.y_log = true;
  PlotSeries s;
  s.x = {1.0, 4.0, 16.0, 64.0, 8.0};
  s.y = {1.0, 0.5, 0.25, 0.125, 0.0};
  s.marker = MarkerShape::kDot;
  spec.series = {s};
  const PlotLayout l = layoutPlot(spec);
  // THEN both axes are logarithmic, and equal ratios are equal distances: the power law is a straight line
  EXPECT_TRUE(l.x.log);
  EXPECT_TRUE(l.y.log);
  const double dx = l.xToPx(4.0) - l.xToPx(1.0);
  EXPECT_NEAR(l.xToPx(64.0) - l.xToPx(16.0), dx, 1e-9);
  EXPECT_NEAR((l.yToPx(0.125) - l.yToPx(0.25)) / dx, (l.yToPx(0.5) - l.yToPx(1.0)) / dx, 1e-9);
  EXPECT_TRUE(std::isnan(l.yToPx(0.0)));
  // AND the point at y = 0 is not drawn but counted, under the plot
  EXPECT_EQ(l.dropped_points, 1u);
  const std::string svg = renderSvg(spec);
  EXPECT_EQ(elements(svg, "circle", "marker").size(), 4u);
  ASSERT_EQ(texts(svg, "dropped-note").size(), 1u);
  EXPECT_NE(texts(svg, "dropped-note")[0].find("1 point(s)"), std::string::npos);
  EXPECT_EQ(svg.find("nan"), std::string::npos) << "no coordinate of a value the axis cannot show";
  // AND a linear plot of the same data draws all five and has no note
  spec.x_log = spec.y_log = false;
  const std::string linear = renderSvg(spec);
  EXPECT_EQ(elements(linear, "circle", "marker").size(), 5u);
  EXPECT_TRUE(texts(linear, "dropped-note").empty());
}

TEST(SvgPlot, GivenXTicksAreDrawnWithTheirLabelsAtTheirPositions) {
  // GIVEN two categories at 0 and 1 named by the caller, the axis from -0.5 to 1.5
  PlotSpec spec;
  spec.series = {markerSeries({0.0, 1.0}, {2.0, 3.0})};
  spec.x_min = -0.5;
  spec.x_max = 1.5;
  spec.x_ticks = {0.0, 1.0};
  spec.x_tick_labels = {"gabriel", "k_<nearest>"};
  const std::string svg = renderSvg(spec);
  const PlotLayout l = layoutPlot(spec);
  // THEN the x tick labels are exactly the names (escaped), each at its category, and no number
  EXPECT_EQ(texts(svg, "tick-x"), (std::vector<std::string>{"gabriel", "k_&lt;nearest&gt;"}));
  const std::vector<std::string> ticks = elements(svg, "text", "tick-x");
  ASSERT_EQ(ticks.size(), 2u);
  EXPECT_NEAR(num(ticks[0], "x"), l.xToPx(0.0), 0.01);
  EXPECT_NEAR(num(ticks[1], "x"), l.xToPx(1.0), 0.01);
  // AND unlabelled given ticks are their numbers; a tick outside the axis is left out
  spec.x_tick_labels.clear();
  spec.x_ticks = {0.25, 1.0, 7.0};
  EXPECT_EQ(texts(renderSvg(spec), "tick-x"), (std::vector<std::string>{"0.25", "1"}));
  // AND labels must be one per tick
  spec.x_tick_labels = {"a"};
  EXPECT_THROW(layoutPlot(spec), std::invalid_argument);
}

TEST(SvgPlot, ErrorBarsSpanMeanPlusMinusErrorAndAreCutAtTheBottomOfALogAxis) {
  PlotSpec spec;
  PlotSeries s = markerSeries({1.0, 2.0, 3.0}, {10.0, 20.0, 30.0});
  s.y_err = {2.0, std::nan(""), 40.0};
  spec.series = {s};
  const PlotLayout l = layoutPlot(spec);
  const std::vector<std::string> bars = elements(renderSvg(spec), "path", "error-bar");
  ASSERT_EQ(bars.size(), 2u) << "NaN: no bar";
  const std::string expected_top = "V" + formatFixed(l.yToPx(8.0), 2);
  EXPECT_NE(attr(bars[0], "d").find("M" + formatFixed(l.xToPx(1.0), 2) + " " + formatFixed(l.yToPx(12.0), 2)),
            std::string::npos)
      << bars[0];
  EXPECT_NE(attr(bars[0], "d").find(expected_top), std::string::npos) << bars[0];
  EXPECT_LE(l.y.lo, -10.0) << "the automatic range holds the bars";
  EXPECT_GE(l.y.hi, 70.0);
  // On a log axis the bar 30 ± 40 reaches below 0: drawn to the plot's bottom.
  spec.y_log = true;
  const PlotLayout log = layoutPlot(spec);
  const std::vector<std::string> log_bars = elements(renderSvg(spec), "path", "error-bar");
  ASSERT_EQ(log_bars.size(), 2u);
  EXPECT_NE(attr(log_bars[1], "d").find("V" + formatFixed(log.bottom_px, 2)), std::string::npos) << log_bars[1];
  // Error bars must be one per point.
  spec.series[0].y_err = {1.0};
  EXPECT_THROW(layoutPlot(spec), std::invalid_argument);
}

TEST(SvgPlot, SeriesDifferInShapeAndDashNotOnlyInColour) {
  std::set<MarkerShape> shapes;
  std::set<std::string> dashes;
  for (std::size_t i = 0; i < 4; ++i) {
    shapes.insert(markerShape(i));
    dashes.insert(dashPattern(i));
  }
  EXPECT_EQ(shapes.size(), 4u);
  EXPECT_EQ(dashes.size(), 4u);
  // A joined marker series draws its line (with its own dash) and a marker of its shape at every point, and its
  // legend swatch shows both.
  PlotSpec spec;
  for (std::size_t i = 0; i < 2; ++i) {
    PlotSeries s = markerSeries({1.0, 2.0}, {1.0, 1.0}, markerShape(i));
    s.joined = true;
    s.dash_pattern = dashPattern(i);
    s.label = "series " + std::to_string(i);
    spec.series.push_back(s);
  }
  const std::string svg = renderSvg(spec);
  const std::vector<std::string> lines = elements(svg, "polyline", "series");
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(attr(lines[0], "stroke-dasharray"), "");
  EXPECT_EQ(attr(lines[1], "stroke-dasharray"), "6 4");
  EXPECT_EQ(elements(svg, "circle", "marker").size(), 2u);
  EXPECT_EQ(elements(svg, "rect", "marker").size(), 2u) << "the second series' squares";
  const std::string legend = svg.substr(svg.find("<g class=\"legend\">"));
  EXPECT_EQ(occurrences(legend, "<line "), 2);
  EXPECT_EQ(occurrences(legend, "<circle "), 1);
  EXPECT_EQ(occurrences(legend, "<rect "), 1);
}

TEST(SvgPlot, ABandCanCoverPartOfTheXRange) {
  PlotSpec spec;
  spec.series = {markerSeries({0.0, 2.0}, {0.0, 2.0})};
  spec.x_min = 0.0;
  spec.x_max = 2.0;
  PlotBand part{0.5, 1.5, "part"};
  part.x_low = 0.5;
  part.x_high = 1.0;
  spec.bands = {part, PlotBand{0.5, 1.5, "whole"}};
  const PlotLayout l = layoutPlot(spec);
  const std::vector<std::string> bands = elements(renderSvg(spec), "rect", "band");
  ASSERT_EQ(bands.size(), 2u);
  EXPECT_NEAR(num(bands[0], "x"), l.xToPx(0.5), 0.01);
  EXPECT_NEAR(num(bands[0], "width"), l.xToPx(1.0) - l.xToPx(0.5), 0.01);
  EXPECT_NEAR(num(bands[1], "x"), l.left_px, 0.01);
  EXPECT_NEAR(num(bands[1], "width"), l.right_px - l.left_px, 0.01);
}

TEST(SvgPlot, ALogAxisIsRefusedInEqualAspectMode) {
  PlotSpec spec;
  spec.equal_aspect = true;
  spec.x_log = true;
  EXPECT_THROW(layoutPlot(spec), std::invalid_argument);
}

}  // namespace
}  // namespace swa::monitor
