// The SVG line-plot writer: nice ticks, layout, NaN gaps, bands, reference lines, equal-aspect XY mode, markers,
// escaping and deterministic, locale-independent output.

#include <gtest/gtest.h>

#include <clocale>
#include <cmath>
#include <limits>
#include <locale>
#include <stdexcept>
#include <string>
#include <vector>

#include "markup_support.h"
#include "swa/monitor/svg_plot.h"

namespace swa::monitor {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

using testing::attr;
using testing::elements;
using testing::num;
using testing::texts;

std::vector<std::pair<double, double>> points(const std::string& polyline) {
  std::vector<std::pair<double, double>> out;
  const std::string list = attr(polyline, "points");
  std::size_t pos = 0;
  while (pos < list.size()) {
    std::size_t end = list.find(' ', pos);
    if (end == std::string::npos) end = list.size();
    const std::string pair = list.substr(pos, end - pos);
    const std::size_t comma = pair.find(',');
    out.emplace_back(std::stod(pair.substr(0, comma)), std::stod(pair.substr(comma + 1)));
    pos = end + 1;
  }
  return out;
}

PlotSeries line(std::vector<double> x, std::vector<double> y, const std::string& label = "") {
  PlotSeries s;
  s.label = label;
  s.x = std::move(x);
  s.y = std::move(y);
  return s;
}

TEST(NiceTicks, ZeroToTenStepsByTwo) {
  // GIVEN data spanning [0, 10] and about 6 ticks WHEN ticked THEN 0, 2, ..., 10 on an unchanged range
  const AxisTicks t = niceTicks(0.0, 10.0, 6);
  EXPECT_EQ(t.values, (std::vector<double>{0, 2, 4, 6, 8, 10}));
  EXPECT_EQ(t.lo, 0.0);
  EXPECT_EQ(t.hi, 10.0);
  EXPECT_EQ(t.step, 2.0);
  EXPECT_EQ(t.decimals, 0);
}

TEST(NiceTicks, RangeIsExtendedOutwardsToTheStep) {
  // GIVEN d_NB-like data in [9.3, 10.7] WHEN ticked THEN the step is 0.5 and the range grows to [9, 11]
  const AxisTicks t = niceTicks(9.3, 10.7, 6);
  EXPECT_EQ(t.step, 0.5);
  EXPECT_EQ(t.values, (std::vector<double>{9.0, 9.5, 10.0, 10.5, 11.0}));
  EXPECT_EQ(t.decimals, 1);
  EXPECT_EQ(formatTick(9.5, t), "9.5");
  EXPECT_EQ(formatTick(10.0, t), "10");
}

TEST(NiceTicks, DecimalStepsAreExactDecimals) {
  // GIVEN [0, 1] WHEN ticked THEN 0.2 steps whose values are the doubles nearest the decimals (no 0.6000000000000001)
  const AxisTicks t = niceTicks(0.0, 1.0, 6);
  EXPECT_EQ(t.step, 0.2);
  ASSERT_EQ(t.values.size(), 6U);
  EXPECT_EQ(t.values[3], 0.6);
  EXPECT_EQ(t.values[5], 1.0);
  // AND small spans get as many decimals as the step needs
  const AxisTicks small = niceTicks(0.0, 0.003, 4);
  EXPECT_EQ(small.step, 0.001);
  EXPECT_EQ(formatTick(small.values[1], small), "0.001");
}

TEST(NiceTicks, NegativeRangesAndStepChoice) {
  const AxisTicks t = niceTicks(-3.0, 7.0, 6);
  EXPECT_EQ(t.step, 2.0);
  EXPECT_EQ(t.values, (std::vector<double>{-4, -2, 0, 2, 4, 6, 8}));
  EXPECT_EQ(formatTick(-4.0, t), "-4");
  EXPECT_EQ(niceStep(100.0, 6), 20.0);
  EXPECT_EQ(niceStep(30.0, 4), 10.0);
  EXPECT_EQ(niceStep(7.0, 2), 10.0);  // 0..10 and 0..20 both give 2 ticks: the tighter range wins
}

TEST(NiceTicks, A120SecondRunIsNotStretchedTo150) {
  // GIVEN a 120 s run WHEN ticked for about 6 ticks THEN 0..120 by 20 (7 ticks), not 0..150 by 50 (4 ticks)
  const AxisTicks t = niceTicks(0.0, 120.0, 6);
  EXPECT_EQ(t.step, 20.0);
  EXPECT_EQ(t.lo, 0.0);
  EXPECT_EQ(t.hi, 120.0);
  EXPECT_EQ(t.values.size(), 7U);
}

TEST(NiceTicks, DegenerateAndBadRangesStillGiveAnAxis) {
  const AxisTicks flat = niceTicks(10.0, 10.0, 6);  // widened to 10 ± 1
  EXPECT_LT(flat.lo, 10.0);
  EXPECT_GT(flat.hi, 10.0);
  EXPECT_GE(flat.values.size(), 2U);
  const AxisTicks zero = niceTicks(0.0, 0.0, 6);
  EXPECT_EQ(zero.lo, -1.0);
  EXPECT_EQ(zero.hi, 1.0);
  const AxisTicks swapped = niceTicks(10.0, 0.0, 6);
  EXPECT_EQ(swapped.lo, 0.0);
  EXPECT_EQ(swapped.hi, 10.0);
  const AxisTicks bad = niceTicks(kNan, 1.0, 6);
  EXPECT_EQ(bad.lo, 0.0);
  EXPECT_EQ(bad.hi, 1.0);
}

TEST(FormatFixed, LocaleIndependentAndNoNegativeZero) {
  EXPECT_EQ(formatFixed(1.25, 2), "1.25");
  EXPECT_EQ(formatFixed(1.5, 3), "1.5");
  EXPECT_EQ(formatFixed(2.0, 2), "2");
  EXPECT_EQ(formatFixed(-0.001, 2), "0");
  EXPECT_EQ(formatFixed(-12.4, 0), "-12");
  EXPECT_EQ(formatFixed(0.125, 2), "0.12");  // the double nearest 0.125 is exact: half to even, as printf does
  EXPECT_EQ(formatFixed(kNan, 2), "nan");
  EXPECT_EQ(formatFixed(1e300, 2), "1e+300");
}

TEST(SvgPlot, TickLabelsSitAtTheirMappedPixelPositions) {
  // GIVEN one series over x in [0, 10], y in [0, 1]
  PlotSpec spec;
  spec.series.push_back(line({0, 5, 10}, {0, 1, 0.5}));
  // WHEN laid out and rendered
  const PlotLayout l = layoutPlot(spec);
  const std::string svg = renderSvg(spec);
  // THEN the x ticks are 0..10 by 2, evenly spread from the left to the right edge of the plot area
  const std::vector<std::string> x_ticks = elements(svg, "text", "tick-x");
  ASSERT_EQ(x_ticks.size(), 6U);
  EXPECT_EQ(texts(svg, "tick-x"), (std::vector<std::string>{"0", "2", "4", "6", "8", "10"}));
  EXPECT_NEAR(num(x_ticks.front(), "x"), l.left_px, 0.01);
  EXPECT_NEAR(num(x_ticks.back(), "x"), l.right_px, 0.01);
  EXPECT_NEAR(num(x_ticks[1], "x") - num(x_ticks[0], "x"), (l.right_px - l.left_px) / 5.0, 0.01);
  // AND the y ticks 0..1 by 0.2 run from the bottom (0) to the top (1)
  const std::vector<std::string> y_ticks = elements(svg, "text", "tick-y");
  EXPECT_EQ(texts(svg, "tick-y"), (std::vector<std::string>{"0", "0.2", "0.4", "0.6", "0.8", "1"}));
  EXPECT_NEAR(num(y_ticks.front(), "y"), l.bottom_px, 0.01);
  EXPECT_NEAR(num(y_ticks.back(), "y"), l.top_px, 0.01);
  // AND the data points land where the axes say: (5, 1) at the middle top
  const std::vector<std::string> lines = elements(svg, "polyline", "series");
  ASSERT_EQ(lines.size(), 1U);
  const auto p = points(lines.front());
  ASSERT_EQ(p.size(), 3U);
  EXPECT_NEAR(p[1].first, 0.5 * (l.left_px + l.right_px), 0.01);
  EXPECT_NEAR(p[1].second, l.top_px, 0.01);
}

TEST(SvgPlot, NanSplitsThePolyline) {
  // GIVEN a series with a NaN in the middle and a lone finite point after a second gap
  PlotSpec spec;
  spec.series.push_back(line({0, 1, 2, 3, 4, 5, 6}, {1, 2, kNan, 4, 5, kNan, 7}));
  // WHEN rendered
  const std::string svg = renderSvg(spec);
  // THEN the two finite runs are separate polylines of 2 points each and the lone point is a dot
  const std::vector<std::string> lines = elements(svg, "polyline", "series");
  ASSERT_EQ(lines.size(), 2U);
  EXPECT_EQ(points(lines[0]).size(), 2U);
  EXPECT_EQ(points(lines[1]).size(), 2U);
  const PlotLayout l = layoutPlot(spec);
  EXPECT_NEAR(points(lines[0]).back().first, l.xToPx(1.0), 0.01);
  EXPECT_NEAR(points(lines[1]).front().first, l.xToPx(3.0), 0.01);
  const std::vector<std::string> dots = elements(svg, "circle", "point");
  ASSERT_EQ(dots.size(), 1U);
  EXPECT_NEAR(num(dots[0], "cx"), l.xToPx(6.0), 0.01);
  // AND a NaN x breaks the line just the same
  spec.series[0] = line({0, kNan, 2, 3}, {1, 1, 1, 1});
  EXPECT_EQ(elements(renderSvg(spec), "polyline", "series").size(), 1U);
  EXPECT_EQ(elements(renderSvg(spec), "circle", "point").size(), 1U);
}

TEST(SvgPlot, BandRectCoversItsRangeOnAForcedAxis) {
  // GIVEN y forced to [0, 20] and the band r ± 10 % around r = 10 m
  PlotSpec spec;
  spec.series.push_back(line({0, 10}, {10, 10}));
  spec.bands.push_back({9.0, 11.0, "r ± 10 %", "#2ca02c", 0.15});
  spec.y_min = 0.0;
  spec.y_max = 20.0;
  const PlotLayout l = layoutPlot(spec);
  ASSERT_EQ(l.y.lo, 0.0);
  ASSERT_EQ(l.y.hi, 20.0);
  // WHEN rendered
  const std::string svg = renderSvg(spec);
  // THEN the band spans the plot width, from y = 11 (top edge) to y = 9, by the linear map of [0, 20] onto the area
  const std::vector<std::string> bands = elements(svg, "rect", "band");
  ASSERT_EQ(bands.size(), 1U);
  const double h = l.bottom_px - l.top_px;
  EXPECT_NEAR(num(bands[0], "x"), l.left_px, 0.01);
  EXPECT_NEAR(num(bands[0], "width"), l.right_px - l.left_px, 0.01);
  EXPECT_NEAR(num(bands[0], "y"), l.bottom_px - 11.0 / 20.0 * h, 0.01);
  EXPECT_NEAR(num(bands[0], "height"), 2.0 / 20.0 * h, 0.01);
  EXPECT_EQ(attr(bands[0], "fill-opacity"), "0.15");
  // AND the band has a legend entry with its (escaped) label
  EXPECT_NE(svg.find(">r ± 10 %</text>"), std::string::npos);
}

TEST(SvgPlot, AutomaticRangeIncludesBandsAndReferenceLines) {
  // GIVEN separation data far above the collision line, and a band above the data
  PlotSpec spec;
  spec.series.push_back(line({0, 10}, {8, 9}));
  spec.lines.push_back({LineOrientation::kHorizontal, 1.5, "collision 1.5 m", "#d62728", true});
  spec.lines.push_back({LineOrientation::kVertical, 12.0, "GNSS lost", "#7f7f7f", true});
  spec.bands.push_back({10.0, 12.0, "", "#2ca02c", 0.15});
  // WHEN laid out THEN both lines and the band are on the axes
  const PlotLayout l = layoutPlot(spec);
  EXPECT_LE(l.y.lo, 1.5);
  EXPECT_GE(l.y.hi, 12.0);
  EXPECT_GE(l.x.hi, 12.0);
  // AND each line is drawn across the plot at its value
  const std::vector<std::string> refs = elements(renderSvg(spec), "line", "ref-line");
  ASSERT_EQ(refs.size(), 2U);
  EXPECT_NEAR(num(refs[0], "y1"), l.yToPx(1.5), 0.01);
  EXPECT_EQ(attr(refs[0], "y1"), attr(refs[0], "y2"));
  EXPECT_NEAR(num(refs[0], "x2") - num(refs[0], "x1"), l.right_px - l.left_px, 0.01);
  EXPECT_NEAR(num(refs[1], "x1"), l.xToPx(12.0), 0.01);
  EXPECT_EQ(attr(refs[1], "x1"), attr(refs[1], "x2"));
}

TEST(SvgPlot, IncludeZeroPullsTheAxisDownToZero) {
  PlotSpec spec;
  spec.series.push_back(line({0, 1}, {0.3, 0.5}));
  EXPECT_GT(layoutPlot(spec).y.lo, 0.0);
  spec.y_include_zero = true;
  EXPECT_EQ(layoutPlot(spec).y.lo, 0.0);
}

TEST(SvgPlot, EqualAspectGivesTheSameScaleOnBothAxes) {
  // GIVEN a trajectory 100 m long in x and 10 m in y, in a 560 x 480 plot
  PlotSpec spec;
  spec.equal_aspect = true;
  spec.width_px = 560;
  spec.height_px = 480;
  spec.series.push_back(line({0, 50, 100}, {0, 10, 5}, "UAV 0"));
  spec.series.push_back(line({20, 30}, {2, 3}, "UAV 1"));
  // WHEN laid out and rendered
  const PlotLayout l = layoutPlot(spec);
  const std::string svg = renderSvg(spec);
  // THEN one metre is the same number of pixels in x and y, and all data fit
  EXPECT_NEAR(l.xScale(), l.yScale(), 1e-9 * l.xScale());
  EXPECT_LE(l.x.lo, 0.0);
  EXPECT_GE(l.x.hi, 100.0);
  EXPECT_LE(l.y.lo, 0.0);
  EXPECT_GE(l.y.hi, 10.0);
  // AND both axes share the tick step, so the tick labels are equally spaced in pixels on both axes
  EXPECT_EQ(l.x.step, l.y.step);
  const std::vector<std::string> xt = elements(svg, "text", "tick-x");
  const std::vector<std::string> yt = elements(svg, "text", "tick-y");
  ASSERT_GE(xt.size(), 2U);
  ASSERT_GE(yt.size(), 2U);
  EXPECT_NEAR(num(xt[1], "x") - num(xt[0], "x"), num(yt[0], "y") - num(yt[1], "y"), 0.02);
  // AND each UAV has a start marker at its first point and an end marker at its last
  const std::vector<std::string> starts = elements(svg, "circle", "start-marker");
  const std::vector<std::string> ends = elements(svg, "rect", "end-marker");
  ASSERT_EQ(starts.size(), 2U);
  ASSERT_EQ(ends.size(), 2U);
  EXPECT_NEAR(num(starts[0], "cx"), l.xToPx(0.0), 0.01);
  EXPECT_NEAR(num(starts[0], "cy"), l.yToPx(0.0), 0.01);
  EXPECT_NEAR(num(ends[0], "x") + 0.5 * num(ends[0], "width"), l.xToPx(100.0), 0.01);
  EXPECT_NEAR(num(ends[0], "y") + 0.5 * num(ends[0], "height"), l.yToPx(5.0), 0.01);
  EXPECT_NEAR(num(ends[1], "x") + 0.5 * num(ends[1], "width"), l.xToPx(30.0), 0.01);
}

TEST(SvgPlot, EqualAspectMarkersUseTheFirstAndLastFinitePoints) {
  PlotSpec spec;
  spec.equal_aspect = true;
  spec.series.push_back(line({kNan, 1, 2, kNan, 3, kNan}, {kNan, 1, 2, kNan, 0, kNan}));
  const PlotLayout l = layoutPlot(spec);
  const std::string svg = renderSvg(spec);
  const std::vector<std::string> starts = elements(svg, "circle", "start-marker");
  const std::vector<std::string> ends = elements(svg, "rect", "end-marker");
  ASSERT_EQ(starts.size(), 1U);
  ASSERT_EQ(ends.size(), 1U);
  EXPECT_NEAR(num(starts[0], "cx"), l.xToPx(1.0), 0.01);
  EXPECT_NEAR(num(ends[0], "x") + 3.5, l.xToPx(3.0), 0.01);
}

TEST(SvgPlot, SeriesColoursAndLegendFollowTheSpec) {
  // GIVEN two runs, the first with the default colour, the second with its own
  PlotSpec spec;
  spec.series.push_back(line({0, 1}, {0, 1}, "swa"));
  spec.series.push_back(line({0, 1}, {1, 0}, "standalone"));
  spec.series[1].colour = "#123456";
  spec.series[1].dashed = true;
  // WHEN rendered
  const std::string svg = renderSvg(spec);
  const std::vector<std::string> lines = elements(svg, "polyline", "series");
  ASSERT_EQ(lines.size(), 2U);
  // THEN the first uses palette colour 0, the second its own, dashed; both are in the legend in order
  EXPECT_EQ(attr(lines[0], "stroke"), paletteColour(0));
  EXPECT_EQ(attr(lines[0], "data-series"), "0");
  EXPECT_EQ(attr(lines[1], "stroke"), "#123456");
  EXPECT_FALSE(attr(lines[1], "stroke-dasharray").empty());
  const std::size_t legend = svg.find("<g class=\"legend\">");
  ASSERT_NE(legend, std::string::npos);
  EXPECT_LT(svg.find(">swa</text>", legend), svg.find(">standalone</text>", legend));
}

TEST(SvgPlot, TextIsEscaped) {
  PlotSpec spec;
  spec.title = "a<b & \"c\" > 'd'";
  spec.y_label = "<y>";
  spec.y_unit = "m&s";
  spec.series.push_back(line({0, 1}, {0, 1}, "<run & \"1\">"));
  const std::string svg = renderSvg(spec);
  EXPECT_NE(svg.find(">a&lt;b &amp; &quot;c&quot; &gt; &#39;d&#39;</text>"), std::string::npos);
  EXPECT_NE(svg.find(">&lt;y&gt; [m&amp;s]</text>"), std::string::npos);
  EXPECT_NE(svg.find(">&lt;run &amp; &quot;1&quot;&gt;</text>"), std::string::npos);
  EXPECT_EQ(svg.find("<run"), std::string::npos);
  EXPECT_EQ(svg.find("<b "), std::string::npos);
  EXPECT_EQ(escapeXml("<&>\"'"), "&lt;&amp;&gt;&quot;&#39;");
}

TEST(SvgPlot, NoDataSaysSo) {
  PlotSpec spec;
  spec.series.push_back(line({0, 1}, {kNan, kNan}, "standalone"));
  const std::string svg = renderSvg(spec);
  EXPECT_EQ(texts(svg, "no-data"), (std::vector<std::string>{"no data"}));
  EXPECT_TRUE(elements(svg, "polyline", "series").empty());
}

TEST(SvgPlot, LongTimeSeriesAreThinnedButKeepTheirExtremes) {
  // GIVEN 100 000 samples of a flat line with one deep spike
  PlotSpec spec;
  PlotSeries s;
  for (int i = 0; i < 100000; ++i) {
    s.x.push_back(i * 0.001);
    s.y.push_back(i == 61234 ? 0.0 : 10.0);
  }
  spec.series.push_back(s);
  // WHEN rendered
  const std::string svg = renderSvg(spec);
  const PlotLayout l = layoutPlot(spec);
  const std::vector<std::string> lines = elements(svg, "polyline", "series");
  ASSERT_EQ(lines.size(), 1U);
  const auto p = points(lines[0]);
  // THEN at most 4 points per pixel column are kept, and the spike is still there
  EXPECT_LE(p.size(), 4U * static_cast<std::size_t>(l.right_px - l.left_px + 2.0));
  // (pixel y grows downwards: the spike to 0 is the largest pixel y)
  double top_px = 1e9;
  double bottom_px = -1e9;
  for (const auto& q : p) {
    top_px = std::min(top_px, q.second);
    bottom_px = std::max(bottom_px, q.second);
  }
  EXPECT_NEAR(bottom_px, l.yToPx(0.0), 0.01);
  EXPECT_NEAR(top_px, l.yToPx(10.0), 0.01);
}

class CommaDecimal : public std::numpunct<char> {
 protected:
  char do_decimal_point() const override { return ','; }
};

TEST(SvgPlot, OutputIsDeterministicAndLocaleIndependent) {
  // GIVEN a plot with fractional coordinates everywhere
  PlotSpec spec;
  spec.title = "drift";
  spec.series.push_back(line({0.1, 0.7, 1.3}, {0.33, 0.25, 0.125}, "swa"));
  spec.bands.push_back({0.2, 0.3, "band", "#2ca02c", 0.15});
  const std::string first = renderSvg(spec);
  // WHEN rendered again, also under a global C++ locale with a decimal comma (and a C one, if installed)
  EXPECT_EQ(renderSvg(spec), first);
  const std::locale previous = std::locale::global(std::locale(std::locale::classic(), new CommaDecimal));
  const std::string c_previous = std::setlocale(LC_ALL, nullptr);
  std::setlocale(LC_ALL, "de_DE.UTF-8");
  const std::string localised = renderSvg(spec);
  std::setlocale(LC_ALL, c_previous.c_str());
  std::locale::global(previous);
  // THEN the output is byte-identical and uses decimal points
  EXPECT_EQ(localised, first);
  EXPECT_NE(first.find("0.25"), std::string::npos);
  EXPECT_NE(texts(first, "tick-y").size(), 0U);
}

TEST(SvgPlot, AMarkerSeriesDrawsEachFinitePointWithItsLabelAndNoLine) {
  // GIVEN a dot series of three points, the second not finite, and a cross series of one point
  PlotSpec spec;
  PlotSeries dots = line({0, kNan, 4}, {0, 1, 2}, "UAVs");
  dots.marker = MarkerShape::kDot;
  dots.marker_px = 6.0;
  dots.point_labels = {"a", "b", "c&d"};
  PlotSeries cross = line({2}, {1});
  cross.marker = MarkerShape::kCross;
  spec.series = {dots, cross};
  // WHEN rendered
  const PlotLayout l = layoutPlot(spec);
  const std::string svg = renderSvg(spec);
  // THEN each finite point is a marker where its data put it, with its label, and nothing joins them
  const std::vector<std::string> circles = elements(svg, "circle", "marker");
  ASSERT_EQ(circles.size(), 2U);
  EXPECT_NEAR(num(circles[1], "cx"), l.xToPx(4.0), 0.01);
  EXPECT_NEAR(num(circles[1], "cy"), l.yToPx(2.0), 0.01);
  EXPECT_EQ(num(circles[1], "r"), 6.0);
  EXPECT_EQ(texts(svg, "point-label"), (std::vector<std::string>{"a", "c&amp;d"}));
  EXPECT_EQ(elements(svg, "path", "marker").size(), 1U);
  EXPECT_TRUE(elements(svg, "polyline", "series").empty());
  EXPECT_TRUE(elements(svg, "circle", "point").empty());
  // AND the legend's swatch of the labelled series is its marker
  const std::size_t legend = svg.find("<g class=\"legend\">");
  ASSERT_NE(legend, std::string::npos);
  EXPECT_NE(svg.find("<circle", legend), std::string::npos);
}

TEST(SvgPlot, EqualAspectShowsTheGivenBoxAndCanLeaveTracksUnmarked) {
  // GIVEN a point at (1, 1), a box of [-10, 10] x [-10, 10] to show and no track markers
  PlotSpec spec;
  spec.equal_aspect = true;
  spec.track_markers = false;
  spec.width_px = 500;
  spec.height_px = 500;
  spec.series.push_back(line({1, 2}, {1, 1}, "track"));
  spec.x_min = -10;
  spec.x_max = 10;
  spec.y_min = -10;
  spec.y_max = 10;
  // WHEN laid out and rendered
  const PlotLayout l = layoutPlot(spec);
  const std::string svg = renderSvg(spec);
  // THEN the whole box is shown, centred, at one scale on both axes
  EXPECT_LE(l.x.lo, -10.0);
  EXPECT_GE(l.x.hi, 10.0);
  EXPECT_LE(l.y.lo, -10.0);
  EXPECT_GE(l.y.hi, 10.0);
  EXPECT_NEAR(l.xToPx(0.0), 0.5 * (l.left_px + l.right_px), 0.01);
  EXPECT_NEAR(l.yToPx(0.0), 0.5 * (l.top_px + l.bottom_px), 0.01);
  EXPECT_NEAR(l.xScale(), l.yScale(), 1e-9 * l.xScale());
  // AND without track markers there is no start or end marker, nor in the legend
  EXPECT_TRUE(elements(svg, "circle", "start-marker").empty());
  EXPECT_TRUE(elements(svg, "rect", "end-marker").empty());
  EXPECT_EQ(svg.find(">start</text>"), std::string::npos);
}

TEST(SvgPlot, RejectsMalformedSpecs) {
  PlotSpec spec;
  spec.series.push_back(line({0, 1, 2}, {0, 1}));
  EXPECT_THROW(renderSvg(spec), std::invalid_argument);
  PlotSpec forced;
  forced.y_min = 2.0;
  forced.y_max = 1.0;
  EXPECT_THROW(layoutPlot(forced), std::invalid_argument);
  PlotSpec tiny;
  tiny.width_px = 10;
  EXPECT_THROW(layoutPlot(tiny), std::invalid_argument);
  PlotSpec labels;
  labels.series.push_back(line({0, 1}, {0, 1}));
  labels.series[0].marker = MarkerShape::kDot;
  labels.series[0].point_labels = {"only one"};
  EXPECT_THROW(layoutPlot(labels), std::invalid_argument);
}

TEST(SvgPlot, IsAStandaloneSvgDocumentElement) {
  PlotSpec spec;
  spec.series.push_back(line({0, 1}, {0, 1}));
  const std::string svg = renderSvg(spec);
  EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0U);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  // Every opened <svg> (outer and the clipping plot area) is closed.
  int open = 0;
  for (std::size_t p = svg.find("<svg "); p != std::string::npos; p = svg.find("<svg ", p + 1)) ++open;
  int close = 0;
  for (std::size_t p = svg.find("</svg>"); p != std::string::npos; p = svg.find("</svg>", p + 1)) ++close;
  EXPECT_EQ(open, 2);
  EXPECT_EQ(close, 2);
}

}  // namespace
}  // namespace swa::monitor
