#pragma once
// A small, dependency-free line-plot writer producing SVG text: several series with a legend, axes with "nice"
// ticks (1, 2 or 5 × 10^k) and labels with units, horizontal bands (an ANEES chi-square band, r ± 10 %), horizontal
// or vertical reference lines, and an equal-aspect XY mode for top-down trajectories with a start and an end marker
// per series.
//
// Output is deterministic: the same PlotSpec gives byte-identical SVG, and every number is written with
// std::to_chars, so the C and C++ locales do not matter. A non-finite x or y breaks a series' line: each run of
// finite points is its own <polyline> (a lone finite point is drawn as a dot). The data are drawn inside a nested
// <svg> viewport, which clips them to the plot area without element ids, so many plots can be inlined into one HTML
// document.
//
// Element classes tests and style sheets can rely on: "title", "tick-x", "tick-y" (tick label <text>, x resp. y
// attribute at the tick), "axis-label", "plot-area" (the clipping viewport), "band" (<rect>), "ref-line" (<line>),
// "series" (<polyline>, attribute data-series = series index), "point" (<circle> of a lone point), "marker" (a
// marker series' <circle> or <path>, data-series), "point-label" (<text> beside a marker, data-series),
// "start-marker", "end-marker", "legend", "no-data".

#include <cstddef>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace swa::monitor {

// Escapes & < > " ' as entities: safe in XML/HTML text and in double- or single-quoted attributes.
std::string escapeXml(std::string_view text);

// Colour i of the plot palette (10 distinguishable colours, cycling).
const std::string& paletteColour(std::size_t index);

// Fixed-point text of `value` with at most `decimals` decimals, trailing zeros dropped, "-0" written as "0";
// locale-independent. Non-finite: "nan" / "inf" / "-inf". |value| >= 1e15 falls back to the shortest round-trip
// form.
std::string formatFixed(double value, int decimals);

struct AxisTicks {
  double lo = 0.0;  // axis range shown
  double hi = 1.0;
  double step = 1.0;           // 1, 2 or 5 × 10^k
  int decimals = 0;            // decimals a tick label needs for this step
  std::vector<double> values;  // the multiples of step in [lo, hi], ascending
};

// Ticks for data in [lo, hi]: the step is the one of the 1-2-5 sequence near (hi - lo) / (target_ticks - 1) whose
// tick count, with the range extended outwards to multiples of it, is closest to target_ticks (a tie goes to the
// step that extends the range less): [0, 120] gets 0..120 by 20, not 0..150 by 50. A degenerate range (lo == hi) is
// widened to lo ± 10 % (± 1 around 0); lo > hi is swapped; non-finite ends give [0, 1]. Tick values are computed as k ×
// step without accumulation (0.3, not 0.30000000000000004).
AxisTicks niceTicks(double lo, double hi, int target_ticks = 6);

// niceTicks(0, span, target_ticks).step.
double niceStep(double span, int target_ticks);

// Tick label text: formatFixed(value, ticks.decimals).
std::string formatTick(double value, const AxisTicks& ticks);

// How a series' points are drawn: joined by a line, or each on its own as a marker (a swarm's UAVs at one instant).
enum class MarkerShape : unsigned char { kNone, kDot, kCross };

struct PlotSeries {
  std::string label;      // legend text; empty: not in the legend
  std::vector<double> x;  // same size as y (renderSvg throws std::invalid_argument otherwise)
  std::vector<double> y;
  std::string colour;  // any SVG colour; empty: paletteColour(series index), dashed from the 11th series on
  bool dashed = false;
  double width_px = 1.5;
  double opacity = 1.0;  // stroke (and dot) opacity, e.g. to put a noisy raw series behind its running mean
  // kDot / kCross: every finite point is a marker of this radius, and no line joins them.
  MarkerShape marker = MarkerShape::kNone;
  double marker_px = 5.0;
  std::vector<std::string> point_labels;  // with a marker: text beside point i; empty, or one per point
};

// A horizontal band y in [low, high] across the plot (drawn under the data).
struct PlotBand {
  double low = 0.0;
  double high = 0.0;
  std::string label;  // legend text; empty: not in the legend
  std::string colour = "#2ca02c";
  double opacity = 0.15;
};

enum class LineOrientation : unsigned char { kHorizontal, kVertical };

// A reference line: y = value (horizontal) or x = value (vertical), e.g. the 1.5 m collision distance or the GNSS
// loss time.
struct PlotLine {
  LineOrientation orientation = LineOrientation::kHorizontal;
  double value = 0.0;
  std::string label;  // legend text; empty: not in the legend
  std::string colour = "#555555";
  bool dashed = true;
};

struct PlotSpec {
  std::string title;
  std::string x_label;
  std::string x_unit;  // shown as "label [unit]"; empty: no brackets
  std::string y_label;
  std::string y_unit;
  std::vector<PlotSeries> series;
  std::vector<PlotBand> bands;
  std::vector<PlotLine> lines;
  // XY mode: one data unit is the same number of pixels on both axes (the shorter data range is widened, centred,
  // to fill the plot area), both axes use the same tick step, and each line series' first and last finite points
  // get a start (hollow circle) and end (filled square) marker when track_markers is set. In this mode forced limits
  // count only when all four are given: they are the box to show (instead of the data's), centred and widened alike.
  bool equal_aspect = false;
  bool track_markers = true;
  // Forced axis limits (NaN: from the data, bands and lines). A forced limit is used as is, not rounded to a tick;
  // data outside are clipped.
  double x_min = std::numeric_limits<double>::quiet_NaN();
  double x_max = std::numeric_limits<double>::quiet_NaN();
  double y_min = std::numeric_limits<double>::quiet_NaN();
  double y_max = std::numeric_limits<double>::quiet_NaN();
  bool y_include_zero = false;  // the automatic y range reaches down (or up) to 0
  int width_px = 720;           // the SVG grows beyond height_px when the legend needs it
  int height_px = 360;
  int target_ticks = 6;
  // Minimum legend width (swatch, gap and text); plots stacked in a report give it the same value so that their
  // plot areas line up. The legend is never narrower than its longest label needs.
  double legend_width_px = 0.0;
};

// Where everything lands, in SVG pixels (y grows downwards).
struct PlotLayout {
  double width_px = 0.0;
  double height_px = 0.0;
  double left_px = 0.0;  // plot area
  double top_px = 0.0;
  double right_px = 0.0;
  double bottom_px = 0.0;
  double legend_px = 0.0;  // legend width right of the plot area (0: no legend)
  AxisTicks x;
  AxisTicks y;
  double xToPx(double value) const { return left_px + (value - x.lo) * xScale(); }
  double yToPx(double value) const { return bottom_px - (value - y.lo) * yScale(); }
  double xScale() const { return (right_px - left_px) / (x.hi - x.lo); }  // px per data unit
  double yScale() const { return (bottom_px - top_px) / (y.hi - y.lo); }
};

// The layout renderSvg uses. Throws std::invalid_argument when a series' x and y differ in size (or its point
// labels are neither none nor one per point), width_px < 200, height_px < 120, target_ticks < 2, or both forced limits
// of an axis are given and not lo < hi.
PlotLayout layoutPlot(const PlotSpec& spec);

// The <svg> element (with xmlns, without an XML declaration), ending in a newline. Long series are thinned in pixel
// space without visible change: in time mode (x non-decreasing) each pixel column keeps its first, lowest, highest
// and last point, so spikes survive; otherwise points closer than 0.5 px to the last kept one are dropped.
std::string renderSvg(const PlotSpec& spec);

}  // namespace swa::monitor
