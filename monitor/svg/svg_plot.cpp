#include "swa/monitor/svg_plot.h"

#include "svg_legend.h"
#include "svg_markers.h"
#include "svg_ticks.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <system_error>

namespace swa::monitor {
namespace {

using namespace svg;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kMarginLeft = 64.0;
constexpr double kMarginRight = 20.0;
constexpr double kMarginTopTitle = 32.0;
constexpr double kMarginTopBare = 12.0;
constexpr double kMarginBottom = 48.0;
constexpr double kLegendGap = 16.0;
constexpr double kLegendRow = 18.0;
constexpr double kCharWidth = 7.0;  // rough advance of a 12 px sans-serif glyph, for sizing the legend

std::size_t codePoints(const std::string& s) {
  std::size_t n = 0;
  for (const char c : s) {
    if ((static_cast<unsigned char>(c) & 0xC0U) != 0x80U) ++n;
  }
  return n;
}

std::string axisTitle(const std::string& label, const std::string& unit) {
  if (unit.empty()) return label;
  if (label.empty()) return "[" + unit + "]";
  return label + " [" + unit + "]";
}

void validateSpec(const PlotSpec& spec) {
  std::string problems;
  for (std::size_t i = 0; i < spec.series.size(); ++i) {
    if (spec.series[i].x.size() != spec.series[i].y.size()) {
      problems += "series " + std::to_string(i) + " has " + std::to_string(spec.series[i].x.size()) + " x and " +
                  std::to_string(spec.series[i].y.size()) + " y values; ";
    }
    const std::size_t labels = spec.series[i].point_labels.size();
    if (labels != 0 && labels != spec.series[i].x.size()) {
      problems += "series " + std::to_string(i) + " has " + std::to_string(labels) + " point labels for " +
                  std::to_string(spec.series[i].x.size()) + " points; ";
    }
    const std::size_t errors = spec.series[i].y_err.size();
    if (errors != 0 && errors != spec.series[i].y.size()) {
      problems += "series " + std::to_string(i) + " has " + std::to_string(errors) + " error bars for " +
                  std::to_string(spec.series[i].y.size()) + " points; ";
    }
  }
  if (!spec.x_tick_labels.empty() && spec.x_tick_labels.size() != spec.x_ticks.size()) {
    problems += std::to_string(spec.x_tick_labels.size()) + " x tick labels for " +
                std::to_string(spec.x_ticks.size()) + " x ticks; ";
  }
  if (spec.equal_aspect && (spec.x_log || spec.y_log)) problems += "a log axis cannot have an equal aspect; ";
  if (spec.width_px < 200) problems += "width_px must be >= 200; ";
  if (spec.height_px < 120) problems += "height_px must be >= 120; ";
  if (spec.target_ticks < 2) problems += "target_ticks must be >= 2; ";
  if (std::isfinite(spec.x_min) && std::isfinite(spec.x_max) && !(spec.x_min < spec.x_max)) {
    problems += "x_min must be < x_max; ";
  }
  if (std::isfinite(spec.y_min) && std::isfinite(spec.y_max) && !(spec.y_min < spec.y_max)) {
    problems += "y_min must be < y_max; ";
  }
  if (!problems.empty()) {
    problems.resize(problems.size() - 2);
    throw std::invalid_argument("PlotSpec: " + problems);
  }
}

// Indices of the points of one finite run [begin, end) that are drawn.
std::vector<std::size_t> thin(const std::vector<double>& sx, const std::vector<double>& sy, std::size_t begin,
                              std::size_t end) {
  std::vector<std::size_t> keep;
  bool monotone = true;
  for (std::size_t i = begin + 1; i < end; ++i) {
    if (sx[i] < sx[i - 1]) {
      monotone = false;
      break;
    }
  }
  if (monotone) {
    std::size_t i = begin;
    while (i < end) {
      const double column = std::floor(sx[i]);
      std::size_t j = i;
      std::size_t lowest = i;
      std::size_t highest = i;
      while (j < end && std::floor(sx[j]) == column) {
        if (sy[j] < sy[lowest]) lowest = j;
        if (sy[j] > sy[highest]) highest = j;
        ++j;
      }
      std::array<std::size_t, 4> picks{i, lowest, highest, j - 1};
      std::sort(picks.begin(), picks.end());
      for (const std::size_t p : picks) {
        if (keep.empty() || keep.back() != p) keep.push_back(p);
      }
      i = j;
    }
    return keep;
  }
  keep.push_back(begin);
  for (std::size_t i = begin + 1; i < end; ++i) {
    const std::size_t last = keep.back();
    if (std::hypot(sx[i] - sx[last], sy[i] - sy[last]) >= 0.5 || i + 1 == end) keep.push_back(i);
  }
  return keep;
}

// Whether `v` can sit on an axis (finite, and positive on a log one).
bool onAxis(double v, bool log) { return std::isfinite(v) && (!log || v > 0.0); }

// The range the data, error bars, bands and lines need on each axis; counts the points a log axis drops.
struct DataRanges {
  Range x;
  Range y;
  std::size_t dropped = 0;
};

DataRanges dataRanges(const PlotSpec& spec) {
  DataRanges r;
  for (const PlotSeries& s : spec.series) {
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      if (!onAxis(s.x[i], spec.x_log) || !onAxis(s.y[i], spec.y_log)) {
        ++r.dropped;
        continue;
      }
      r.x.add(s.x[i]);
      r.y.add(s.y[i]);
      const double e = i < s.y_err.size() ? s.y_err[i] : kNan;
      if (!(e > 0.0) || !std::isfinite(e)) continue;
      r.y.add(s.y[i] + e);
      // On a log axis a bar reaching near 0 would stretch the axis over decades no point needs: its lower end counts
      // down to a decade below its point, and reaches on to the plot's edge.
      if (onAxis(s.y[i] - e, spec.y_log)) r.y.add(spec.y_log ? std::max(s.y[i] - e, s.y[i] / 10.0) : s.y[i] - e);
    }
  }
  if (spec.equal_aspect) return r;
  for (const PlotBand& b : spec.bands) {
    for (const double v : {b.low, b.high}) {
      if (onAxis(v, spec.y_log)) r.y.add(v);
    }
  }
  for (const PlotLine& line : spec.lines) {
    const bool horizontal = line.orientation == LineOrientation::kHorizontal;
    if (onAxis(line.value, horizontal ? spec.y_log : spec.x_log)) (horizontal ? r.y : r.x).add(line.value);
  }
  return r;
}

// Ticks of a log axis over `data`, a forced end (if positive) kept as given.
AxisTicks logAxisTicks(const Range& data, double forced_lo, double forced_hi, int target_ticks) {
  const bool has_lo = std::isfinite(forced_lo) && forced_lo > 0.0;
  const bool has_hi = std::isfinite(forced_hi) && forced_hi > 0.0;
  AxisTicks t = logTicks(has_lo ? forced_lo : data.lo, has_hi ? forced_hi : data.hi, target_ticks);
  if (!has_lo && !has_hi) return t;
  if (has_lo) t.lo = forced_lo;
  if (has_hi) t.hi = forced_hi;
  std::vector<double> inside;
  for (const double v : t.values) {
    if (v >= t.lo && v <= t.hi) inside.push_back(v);
  }
  t.values = std::move(inside);
  return t;
}

// The caller's ticks (those within the axis) replace the automatic ones.
void useGivenTicks(AxisTicks& t, const std::vector<double>& ticks, const std::vector<std::string>& labels) {
  if (ticks.empty()) return;
  constexpr double kSlack = 1e-9;    // a tick on the axis end, give or take rounding, is drawn
  constexpr int kGivenDecimals = 6;  // an unlabelled given tick is written as the number it is (0.25, not "0")
  t.values.clear();
  t.labels.clear();
  for (std::size_t i = 0; i < ticks.size(); ++i) {
    const double f = t.fraction(ticks[i]);
    if (!std::isfinite(f) || f < -kSlack || f > 1.0 + kSlack) continue;
    t.values.push_back(ticks[i]);
    t.labels.push_back(labels.empty() ? formatFixed(ticks[i], kGivenDecimals) : labels[i]);
  }
}

// The text of tick i of `t`, escaped.
std::string tickText(const AxisTicks& t, std::size_t i) {
  return i < t.labels.size() ? escapeXml(t.labels[i]) : formatTick(t.values[i], t);
}

// The stroke-dasharray of a line series: its own pattern, or the default dash when dashed.
std::string seriesDash(const PlotSeries& s, std::size_t index) {
  if (!s.dash_pattern.empty()) return " stroke-dasharray=\"" + escapeXml(s.dash_pattern) + "\"";
  return dashAttr(seriesDashed(s, index), "6 4");
}

// Every error bar of series `index`: a vertical stroke with short caps, in the series' colour.
void renderErrorBars(std::string& out, const PlotSeries& s, std::size_t index, const PlotLayout& l) {
  constexpr double kCapHalfWidth = 4.0;  // px: wide enough to see, narrower than the markers are apart
  const std::string colour = escapeXml(seriesColour(s, index));
  for (std::size_t i = 0; i < s.y_err.size(); ++i) {
    const double e = s.y_err[i];
    if (!(e > 0.0) || !std::isfinite(e) || !l.plottable(s.x[i], s.y[i])) continue;
    const double x = l.xToPx(s.x[i]);
    const double top = l.yToPx(s.y[i] + e);
    const double low = s.y[i] - e;
    // Below what a log axis shows: down to the plot's bottom edge (and no cap there, as the bar goes on).
    const bool cut = !l.plottable(s.x[i], low);
    const double bottom = cut ? l.bottom_px : l.yToPx(low);
    std::string d = "M" + px(x) + " " + px(top) + "V" + px(bottom) + "M" + px(x - kCapHalfWidth) + " " + px(top) + "H" +
                    px(x + kCapHalfWidth);
    if (!cut) d += "M" + px(x - kCapHalfWidth) + " " + px(bottom) + "H" + px(x + kCapHalfWidth);
    out += "<path class=\"error-bar\" data-series=\"" + std::to_string(index) + "\" d=\"" + d +
           "\" fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"1.25\"/>\n";
  }
}

}  // namespace

bool PlotLayout::plottable(double xv, double yv) const {
  return std::isfinite(xv) && std::isfinite(yv) && (!x.log || xv > 0.0) && (!y.log || yv > 0.0);
}

MarkerShape markerShape(std::size_t index) {
  static constexpr std::array<MarkerShape, 5> kShapes{MarkerShape::kDot, MarkerShape::kSquare, MarkerShape::kTriangle,
                                                      MarkerShape::kDiamond, MarkerShape::kCross};
  return kShapes[index % kShapes.size()];
}

const std::string& dashPattern(std::size_t index) {
  static const std::array<std::string, 4> kPatterns{"", "6 4", "2 3", "8 3 2 3"};
  return kPatterns[index % kPatterns.size()];
}

std::string escapeXml(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
        break;
    }
  }
  return out;
}

const std::string& paletteColour(std::size_t index) {
  // matplotlib's tab10: distinguishable, and the first two (blue, orange) read well side by side.
  static const std::array<std::string, 10> kPalette{"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                                    "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  return kPalette[index % kPalette.size()];
}

PlotLayout layoutPlot(const PlotSpec& spec) {
  validateSpec(spec);
  const std::vector<LegendEntry> legend = legendEntries(spec);
  std::size_t legend_chars = 0;
  for (const LegendEntry& e : legend) legend_chars = std::max(legend_chars, codePoints(e.label));
  const double legend_width = legend.empty()
                                  ? 0.0
                                  : std::max(spec.legend_width_px, kLegendGap + kLegendSwatch + 6.0 +
                                                                       kCharWidth * static_cast<double>(legend_chars));

  PlotLayout l;
  l.legend_px = legend_width;
  l.left_px = kMarginLeft;
  l.top_px = spec.title.empty() ? kMarginTopBare : kMarginTopTitle;
  const double right_margin = kMarginRight + legend_width;
  l.width_px = std::max(static_cast<double>(spec.width_px), l.left_px + 120.0 + right_margin);
  l.height_px =
      std::max(static_cast<double>(spec.height_px), l.top_px + kLegendRow * static_cast<double>(legend.size()) + 12.0);
  l.right_px = l.width_px - right_margin;
  l.bottom_px = l.height_px - kMarginBottom;

  const DataRanges ranges = dataRanges(spec);
  Range xr = ranges.x;
  Range yr = ranges.y;
  l.dropped_points = ranges.dropped;

  if (spec.equal_aspect) {
    const bool box = std::isfinite(spec.x_min) && std::isfinite(spec.x_max) && std::isfinite(spec.y_min) &&
                     std::isfinite(spec.y_max);
    if (box) {
      xr = {spec.x_min, spec.x_max};
      yr = {spec.y_min, spec.y_max};
    } else if (xr.empty()) {
      xr.add(0.0);
      yr.add(0.0);
    }
    // 5 % of the larger span as padding, so markers on the edge stay inside; at least 1 unit around a single point.
    const double pad = box ? 0.0 : std::max(0.05 * std::max(xr.hi - xr.lo, yr.hi - yr.lo), 1e-9);
    const double x_span = std::max(xr.hi - xr.lo + 2.0 * pad, 2.0);
    const double y_span = std::max(yr.hi - yr.lo + 2.0 * pad, 2.0);
    const double w = l.right_px - l.left_px;
    const double h = l.bottom_px - l.top_px;
    const double scale = std::min(w / x_span, h / y_span);
    const double cx = 0.5 * (xr.lo + xr.hi);
    const double cy = 0.5 * (yr.lo + yr.hi);
    const double half_w = 0.5 * w / scale;
    const double half_h = 0.5 * h / scale;
    // One step for both axes, chosen on the longer one.
    const double half_long = std::max(half_w, half_h);
    const double c_long = half_w >= half_h ? cx : cy;
    const Step step = stepFor(c_long - half_long, c_long + half_long, spec.target_ticks, false);
    l.x = ticksFromStep(step, cx - half_w, cx + half_w);
    l.y = ticksFromStep(step, cy - half_h, cy + half_h);
    return l;
  }

  l.x = spec.x_log ? logAxisTicks(xr, spec.x_min, spec.x_max, spec.target_ticks)
                   : axisTicks(xr, spec.x_min, spec.x_max, false, spec.target_ticks);
  l.y = spec.y_log ? logAxisTicks(yr, spec.y_min, spec.y_max, spec.target_ticks)
                   : axisTicks(yr, spec.y_min, spec.y_max, spec.y_include_zero, spec.target_ticks);
  useGivenTicks(l.x, spec.x_ticks, spec.x_tick_labels);
  return l;
}

std::string renderSvg(const PlotSpec& spec) {
  const PlotLayout l = layoutPlot(spec);
  const double w = l.right_px - l.left_px;
  const double h = l.bottom_px - l.top_px;
  std::string out;
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + px(l.width_px) + "\" height=\"" + px(l.height_px) +
         "\" viewBox=\"0 0 " + px(l.width_px) + " " + px(l.height_px) +
         "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\"12\">\n";
  out +=
      "<rect x=\"0\" y=\"0\" width=\"" + px(l.width_px) + "\" height=\"" + px(l.height_px) + "\" fill=\"#ffffff\"/>\n";
  if (!spec.title.empty()) {
    out += "<text class=\"title\" x=\"" + px(0.5 * l.width_px) +
           "\" y=\"20\" text-anchor=\"middle\" font-size=\"14\" font-weight=\"bold\">" + escapeXml(spec.title) +
           "</text>\n";
  }

  // Grid, frame, ticks and their labels.
  out += "<g class=\"grid\" stroke=\"#e6e6e6\" stroke-width=\"1\">\n";
  for (const double v : l.x.values) {
    const std::string x = px(l.xToPx(v));
    out += "<line x1=\"" + x + "\" y1=\"" + px(l.top_px) + "\" x2=\"" + x + "\" y2=\"" + px(l.bottom_px) + "\"/>\n";
  }
  for (const double v : l.y.values) {
    const std::string y = px(l.yToPx(v));
    out += "<line x1=\"" + px(l.left_px) + "\" y1=\"" + y + "\" x2=\"" + px(l.right_px) + "\" y2=\"" + y + "\"/>\n";
  }
  out += "</g>\n";
  out += "<g class=\"axes\" stroke=\"#333333\" stroke-width=\"1\">\n";
  out += "<rect x=\"" + px(l.left_px) + "\" y=\"" + px(l.top_px) + "\" width=\"" + px(w) + "\" height=\"" + px(h) +
         "\" fill=\"none\"/>\n";
  for (const double v : l.x.values) {
    const std::string x = px(l.xToPx(v));
    out += "<line x1=\"" + x + "\" y1=\"" + px(l.bottom_px) + "\" x2=\"" + x + "\" y2=\"" + px(l.bottom_px + 4.0) +
           "\"/>\n";
  }
  for (const double v : l.y.values) {
    const std::string y = px(l.yToPx(v));
    out +=
        "<line x1=\"" + px(l.left_px - 4.0) + "\" y1=\"" + y + "\" x2=\"" + px(l.left_px) + "\" y2=\"" + y + "\"/>\n";
  }
  out += "</g>\n";
  out += "<g class=\"tick-labels\" fill=\"#333333\">\n";
  for (std::size_t i = 0; i < l.x.values.size(); ++i) {
    out += "<text class=\"tick-x\" x=\"" + px(l.xToPx(l.x.values[i])) + "\" y=\"" + px(l.bottom_px + 16.0) +
           "\" text-anchor=\"middle\">" + tickText(l.x, i) + "</text>\n";
  }
  for (std::size_t i = 0; i < l.y.values.size(); ++i) {
    out += "<text class=\"tick-y\" x=\"" + px(l.left_px - 7.0) + "\" y=\"" + px(l.yToPx(l.y.values[i])) +
           "\" dy=\"0.35em\" text-anchor=\"end\">" + tickText(l.y, i) + "</text>\n";
  }
  out += "</g>\n";
  const std::string x_title = axisTitle(spec.x_label, spec.x_unit);
  const std::string y_title = axisTitle(spec.y_label, spec.y_unit);
  if (!x_title.empty()) {
    out += "<text class=\"axis-label\" x=\"" + px(0.5 * (l.left_px + l.right_px)) + "\" y=\"" + px(l.height_px - 12.0) +
           "\" text-anchor=\"middle\">" + escapeXml(x_title) + "</text>\n";
  }
  if (!y_title.empty()) {
    const std::string cy = px(0.5 * (l.top_px + l.bottom_px));
    out += "<text class=\"axis-label\" x=\"16\" y=\"" + cy + "\" text-anchor=\"middle\" transform=\"rotate(-90 16 " +
           cy + ")\">" + escapeXml(y_title) + "</text>\n";
  }

  // The data, clipped to the plot area by a nested viewport whose user space is the outer one.
  out += "<svg class=\"plot-area\" x=\"" + px(l.left_px) + "\" y=\"" + px(l.top_px) + "\" width=\"" + px(w) +
         "\" height=\"" + px(h) + "\" viewBox=\"" + px(l.left_px) + " " + px(l.top_px) + " " + px(w) + " " + px(h) +
         "\" overflow=\"hidden\">\n";
  for (const PlotBand& b : spec.bands) {
    if (!std::isfinite(b.low) || !std::isfinite(b.high)) continue;
    const double top = std::max(b.low, b.high);
    const double low = std::min(b.low, b.high);
    if (!onAxis(top, l.y.log)) continue;
    const double y_top = l.yToPx(top);
    const double y_bottom = onAxis(low, l.y.log) ? l.yToPx(low) : l.bottom_px;
    const double x_left = onAxis(b.x_low, l.x.log) ? l.xToPx(b.x_low) : l.left_px;
    const double x_right = onAxis(b.x_high, l.x.log) ? l.xToPx(b.x_high) : l.right_px;
    out += "<rect class=\"band\" x=\"" + px(x_left) + "\" y=\"" + px(y_top) + "\" width=\"" + px(x_right - x_left) +
           "\" height=\"" + px(y_bottom - y_top) + "\" fill=\"" + escapeXml(b.colour) + "\" fill-opacity=\"" +
           formatFixed(b.opacity, 3) + "\"/>\n";
  }
  for (const PlotLine& line : spec.lines) {
    const bool horizontal = line.orientation == LineOrientation::kHorizontal;
    if (!onAxis(line.value, horizontal ? l.y.log : l.x.log)) continue;
    std::string coords;
    if (line.orientation == LineOrientation::kHorizontal) {
      const std::string y = px(l.yToPx(line.value));
      coords = "x1=\"" + px(l.left_px) + "\" y1=\"" + y + "\" x2=\"" + px(l.right_px) + "\" y2=\"" + y + "\"";
    } else {
      const std::string x = px(l.xToPx(line.value));
      coords = "x1=\"" + x + "\" y1=\"" + px(l.top_px) + "\" x2=\"" + x + "\" y2=\"" + px(l.bottom_px) + "\"";
    }
    out += "<line class=\"ref-line\" " + coords + " stroke=\"" + escapeXml(line.colour) + "\" stroke-width=\"1.5\"" +
           dashAttr(line.dashed, "5 4") + "/>\n";
  }
  bool any_point = false;
  for (std::size_t si = 0; si < spec.series.size(); ++si) {
    const PlotSeries& s = spec.series[si];
    renderErrorBars(out, s, si, l);
    if (s.marker != MarkerShape::kNone && !s.joined) {
      any_point = renderMarkers(out, s, si, l) || any_point;
      continue;
    }
    const std::string colour = escapeXml(seriesColour(s, si));
    const std::string index = std::to_string(si);
    const std::string opacity = s.opacity < 1.0
                                    ? " stroke-opacity=\"" + formatFixed(std::max(s.opacity, 0.0), 3) +
                                          "\" fill-opacity=\"" + formatFixed(std::max(s.opacity, 0.0), 3) + "\""
                                    : std::string();
    std::vector<double> sx(s.x.size());
    std::vector<double> sy(s.y.size());
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      const bool shown = l.plottable(s.x[i], s.y[i]);
      sx[i] = shown ? l.xToPx(s.x[i]) : kNan;
      sy[i] = shown ? l.yToPx(s.y[i]) : kNan;
    }
    std::size_t i = 0;
    while (i < sx.size()) {
      if (std::isnan(sx[i])) {
        ++i;
        continue;
      }
      std::size_t end = i;
      while (end < sx.size() && !std::isnan(sx[end])) ++end;
      any_point = true;
      if (end - i == 1 && s.marker != MarkerShape::kNone) {
        // A joined marker series' lone point: its marker (drawn below) is the point.
      } else if (end - i == 1) {
        out += "<circle class=\"point\" data-series=\"" + index + "\" cx=\"" + px(sx[i]) + "\" cy=\"" + px(sy[i]) +
               "\" r=\"2\" fill=\"" + colour + "\"" + opacity + "/>\n";
      } else {
        std::string points;
        for (const std::size_t k : thin(sx, sy, i, end)) {
          if (!points.empty()) points += ' ';
          points += px(sx[k]) + "," + px(sy[k]);
        }
        out += "<polyline class=\"series\" data-series=\"" + index + "\" fill=\"none\" stroke=\"" + colour +
               "\" stroke-width=\"" + formatFixed(s.width_px, 2) + "\" stroke-linejoin=\"round\"" + opacity +
               seriesDash(s, si) + " points=\"" + points + "\"/>\n";
      }
      i = end;
    }
    if (s.marker != MarkerShape::kNone) renderMarkers(out, s, si, l);
  }
  if (spec.equal_aspect && spec.track_markers) renderTrackMarkers(out, spec, l);
  if (l.dropped_points > 0) {
    out += "<text class=\"dropped-note\" x=\"" + px(l.left_px + 6.0) + "\" y=\"" + px(l.bottom_px - 6.0) +
           "\" fill=\"#888888\" font-size=\"11\">" + std::to_string(l.dropped_points) +
           " point(s) &lt;= 0 not shown on the log axis</text>\n";
  }
  if (!any_point) {
    out += "<text class=\"no-data\" x=\"" + px(0.5 * (l.left_px + l.right_px)) + "\" y=\"" +
           px(0.5 * (l.top_px + l.bottom_px)) + "\" text-anchor=\"middle\" fill=\"#888888\">no data</text>\n";
  }
  out += "</svg>\n";

  const std::vector<LegendEntry> legend = legendEntries(spec);
  if (!legend.empty()) {
    out += "<g class=\"legend\">\n";
    const double x = l.right_px + kLegendGap;
    for (std::size_t i = 0; i < legend.size(); ++i) {
      const double y = l.top_px + 9.0 + kLegendRow * static_cast<double>(i);
      renderLegendSwatch(out, legend[i], x, y);
      out += "<text x=\"" + px(x + kLegendSwatch + 6.0) + "\" y=\"" + px(y) + "\" dy=\"0.35em\">" +
             escapeXml(legend[i].label) + "</text>\n";
    }
    out += "</g>\n";
  }
  out += "</svg>\n";
  return out;
}

}  // namespace swa::monitor
