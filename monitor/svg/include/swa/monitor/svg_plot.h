#pragma once
// A small, dependency-free line-plot writer producing SVG text: several series with a legend, axes with "nice"
// ticks (1, 2 or 5 × 10^k) and labels with units, horizontal bands (an ANEES chi-square band, r ± 5 %), horizontal
// or vertical reference lines, and an equal-aspect XY mode for top-down trajectories with a start and an end marker
// per series. For a study's summary plots: logarithmic axes (a power law is a straight line), ticks of the caller's
// choosing with their own labels (categories: "gabriel", "k_nearest" at 0 and 1), markers of five shapes joined by a
// line or not, and vertical error bars.
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
// "start-marker", "end-marker", "legend", "no-data", "error-bar" (<path>, data-series), "dropped-note" (<text>: how
// many points a logarithmic axis could not show).

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
  // A logarithmic axis: lo and hi are still data values (> 0), positions go by log10, values are 1-2-5 × 10^k (or
  // the caller's ticks), and step is 0.
  bool log = false;
  std::vector<std::string> labels;  // one per value, or empty: formatTick of each
  // Where `value` sits between lo (0) and hi (1); NaN for a value <= 0 on a log axis.
  double fraction(double value) const;
};

// Ticks for data in [lo, hi]: the step is the one of the 1-2-5 sequence near (hi - lo) / (target_ticks - 1) whose
// tick count, with the range extended outwards to multiples of it, is closest to target_ticks (a tie goes to the
// step that extends the range less): [0, 120] gets 0..120 by 20, not 0..150 by 50. A degenerate range (lo == hi) is
// widened to lo ± 10 % (± 1 around 0); lo > hi is swapped; non-finite ends give [0, 1]. Tick values are computed as k ×
// step without accumulation (0.3, not 0.30000000000000004).
AxisTicks niceTicks(double lo, double hi, int target_ticks = 6);

// niceTicks(0, span, target_ticks).step.
double niceStep(double span, int target_ticks);

// Ticks of a logarithmic axis for positive data in [lo, hi] (non-positive or non-finite ends: [1, 10]): the range is
// padded by 5 % of its decades on each side and is at least a factor 3 wide (so that two ticks fit); the ticks are
// the powers of ten if at least 3 of them fall inside, else 1, 2 and 5 × 10^k if 3 do, else 1..9 × 10^k. Too many
// decades keep every second (third, ...) one, at most 2 × target_ticks ticks.
AxisTicks logTicks(double lo, double hi, int target_ticks = 6);

// Tick label text: formatFixed(value, ticks.decimals); on a log axis with the decimals the value itself needs.
std::string formatTick(double value, const AxisTicks& ticks);

// How a series' points are drawn: joined by a line, or each on its own as a marker (a swarm's UAVs at one instant).
// kDot, kSquare, kTriangle and kDiamond are filled (white rim); kCross is two strokes.
enum class MarkerShape : unsigned char { kNone, kDot, kCross, kSquare, kTriangle, kDiamond };

// Shape i of a sequence that tells series apart without colour: dot, square, triangle, diamond, cross, cycling.
MarkerShape markerShape(std::size_t index);
// Dash pattern i ("" solid, then "6 4", "2 3", "8 3 2 3", cycling): the same use for lines.
const std::string& dashPattern(std::size_t index);

struct PlotSeries {
  std::string label;      // legend text; empty: not in the legend
  std::vector<double> x;  // same size as y (renderSvg throws std::invalid_argument otherwise)
  std::vector<double> y;
  std::string colour;  // any SVG colour; empty: paletteColour(series index), dashed from the 11th series on
  bool dashed = false;
  std::string dash_pattern;  // a stroke-dasharray ("2 3"); non-empty: the line is dashed so, whatever `dashed` says
  double width_px = 1.5;
  double opacity = 1.0;  // stroke (and dot) opacity, e.g. to put a noisy raw series behind its running mean
  // A marker shape: every finite point is a marker of this radius, and no line joins them unless `joined`.
  MarkerShape marker = MarkerShape::kNone;
  double marker_px = 5.0;
  bool joined = false;                    // with a marker: the points are also joined by a line, as a line series' are
  std::vector<std::string> point_labels;  // with a marker: text beside point i; empty, or one per point
  // A vertical error bar y[i] ± y_err[i] at point i (NaN or <= 0: none); empty, or one per point. The bars' ends
  // count in the automatic y range, so no bar is cut off; on a log axis a lower end counts down to a decade below its
  // point, and a bar reaching further (or to 0 or below) is drawn down to the bottom of the plot.
  std::vector<double> y_err;
};

// A horizontal band y in [low, high] across the plot (drawn under the data), or only across x in [x_low, x_high]
// (each given end; NaN: the plot's edge), e.g. a different band at each grid point of a study.
struct PlotBand {
  double low = 0.0;
  double high = 0.0;
  std::string label;  // legend text; empty: not in the legend
  std::string colour = "#2ca02c";
  double opacity = 0.15;
  double x_low = std::numeric_limits<double>::quiet_NaN();
  double x_high = std::numeric_limits<double>::quiet_NaN();
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
  bool y_include_zero = false;  // the automatic y range reaches down (or up) to 0 (ignored on a log y axis)
  // Logarithmic axes (logTicks; not with equal_aspect). Points with a value <= 0 on a log axis are not drawn and
  // are counted in a "dropped-note" under the plot; such band ends and error bar ends are cut at the plot's edge.
  bool x_log = false;
  bool y_log = false;
  // The caller's x ticks, instead of the automatic ones (those within the axis range are drawn), e.g. the
  // categories of a study's axis at 0, 1, 2 ...; labels: one per tick, or none (the numbers).
  std::vector<double> x_ticks;
  std::vector<std::string> x_tick_labels;
  int width_px = 720;  // the SVG grows beyond height_px when the legend needs it
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
  std::size_t dropped_points = 0;  // points of the series with a value <= 0 on a log axis: not drawn
  // NaN for a value a log axis cannot show.
  double xToPx(double value) const { return left_px + x.fraction(value) * (right_px - left_px); }
  double yToPx(double value) const { return bottom_px - y.fraction(value) * (bottom_px - top_px); }
  double xScale() const { return (right_px - left_px) / (x.hi - x.lo); }  // px per data unit (a linear axis)
  double yScale() const { return (bottom_px - top_px) / (y.hi - y.lo); }
  // Whether (x, y) is drawn: both finite and, on a log axis, positive.
  bool plottable(double xv, double yv) const;
};

// The layout renderSvg uses. Throws std::invalid_argument when a series' x and y differ in size (or its point
// labels or error bars are neither none nor one per point), width_px < 200, height_px < 120, target_ticks < 2, both
// forced limits of an axis are given and not lo < hi, x_tick_labels are neither none nor one per x tick, or a log
// axis is asked for in equal-aspect mode.
PlotLayout layoutPlot(const PlotSpec& spec);

// The <svg> element (with xmlns, without an XML declaration), ending in a newline. Long series are thinned in pixel
// space without visible change: in time mode (x non-decreasing) each pixel column keeps its first, lowest, highest
// and last point, so spikes survive; otherwise points closer than 0.5 px to the last kept one are dropped.
std::string renderSvg(const PlotSpec& spec);

}  // namespace swa::monitor
