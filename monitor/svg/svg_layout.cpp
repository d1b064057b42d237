#include "svg_layout.h"

#include "svg_legend.h"
#include "svg_ticks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace swa::monitor {
namespace {

using namespace svg;

constexpr double kMarginLeft = 64.0;
constexpr double kMarginRight = 20.0;
constexpr double kMarginTopTitle = 32.0;
constexpr double kMarginTopBare = 12.0;
constexpr double kMarginBottom = 48.0;
constexpr double kCharWidth = 7.0;  // rough advance of a 12 px sans-serif glyph, for sizing the legend

std::size_t codePoints(const std::string& s) {
  std::size_t n = 0;
  for (const char c : s) {
    if ((static_cast<unsigned char>(c) & 0xC0U) != 0x80U) ++n;
  }
  return n;
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

}  // namespace

namespace svg {

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

}  // namespace svg

bool PlotLayout::plottable(double xv, double yv) const {
  return std::isfinite(xv) && std::isfinite(yv) && (!x.log || xv > 0.0) && (!y.log || yv > 0.0);
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

}  // namespace swa::monitor
