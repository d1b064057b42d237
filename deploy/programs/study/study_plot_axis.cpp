#include "study_plot_axis.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "swa/monitor/swarm_metrics.h"

namespace swa::study {
namespace {

using monitor::kNaN;

// The drift plot goes log-log when the key's values span at least this factor: over less, a log axis shows hardly
// anything a linear one does not (the shipped drift study's 4..32 UAVs span 8).
constexpr double kLogSpanFactor = 4.0;
// The series at one value spread over this share of the smallest distance between two values (categories: 1), so
// equal means stay visible side by side and a value's markers are never nearer another value than their own.
constexpr double kSeriesSpread = 0.3;

std::optional<double> numberOf(const std::string& text) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

// A position on the axis' own scale (log10 on a log axis), and back.
double scaled(const XAxis& x, double v) { return x.log ? std::log10(v) : v; }
double unscaled(const XAxis& x, double s) { return x.log ? std::pow(10.0, s) : s; }

// The smallest distance between two of the axis' values, on its scale (1 with one value).
double smallestGap(const XAxis& x) {
  std::vector<double> s;
  for (const double v : x.at) s.push_back(scaled(x, v));
  std::sort(s.begin(), s.end());
  double gap = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < s.size(); ++i) {
    if (s[i] > s[i - 1]) gap = std::min(gap, s[i] - s[i - 1]);
  }
  return std::isfinite(gap) ? gap : 1.0;
}

// The distance between two series' markers at one value, on the axis' scale.
double seriesStep(const XAxis& x, std::size_t count) {
  return kSeriesSpread * smallestGap(x) / static_cast<double>(std::max<std::size_t>(count, 1));
}

}  // namespace

XAxis xAxisOf(const Axis& a, bool log_if_wide) {
  XAxis x;
  x.axis = &a;
  for (const std::string& v : a.values) {
    const std::optional<double> number = numberOf(v);
    x.numeric = x.numeric && number.has_value();
    x.at.push_back(number.value_or(kNaN));
  }
  if (!x.numeric) {
    for (std::size_t j = 0; j < x.at.size(); ++j) x.at[j] = static_cast<double>(j);
    return x;
  }
  const auto [lo, hi] = std::minmax_element(x.at.begin(), x.at.end());
  x.log = log_if_wide && *lo > 0.0 && *hi >= kLogSpanFactor * *lo;
  return x;
}

double shiftedX(const XAxis& x, std::size_t j, std::size_t si, std::size_t count) {
  if (count < 2) return x.at[j];
  const double offset = (static_cast<double>(si) - 0.5 * static_cast<double>(count - 1)) * seriesStep(x, count);
  return unscaled(x, scaled(x, x.at[j]) + offset);
}

std::pair<double, double> slotOf(const XAxis& x, std::size_t j, std::size_t si, std::size_t count) {
  const double centre = scaled(x, shiftedX(x, j, si, count));
  const double half = 0.5 * seriesStep(x, count);
  return {unscaled(x, centre - half), unscaled(x, centre + half)};
}

std::pair<double, double> extentOf(const XAxis& x, std::size_t j) {
  const double s = scaled(x, x.at[j]);
  double below = -std::numeric_limits<double>::infinity();
  double above = std::numeric_limits<double>::infinity();
  for (const double v : x.at) {
    const double t = scaled(x, v);
    if (t < s) below = std::max(below, t);
    if (t > s) above = std::min(above, t);
  }
  return {std::isfinite(below) ? unscaled(x, 0.5 * (below + s)) : kNaN,
          std::isfinite(above) ? unscaled(x, 0.5 * (above + s)) : kNaN};
}

std::vector<std::size_t> indexOf(const StudyPlan& plan, std::size_t point) {
  std::vector<std::size_t> index(plan.axes.size());
  for (std::size_t k = plan.axes.size(); k-- > 0;) {
    index[k] = point % plan.axes[k].values.size();
    point /= plan.axes[k].values.size();
  }
  return index;
}

std::vector<PointSeries> seriesAlong(const StudyPlan& plan, std::size_t axis) {
  std::map<std::vector<std::size_t>, PointSeries> by_rest;
  for (std::size_t point = 0; point < pointCount(plan); ++point) {
    std::vector<std::size_t> index = indexOf(plan, point);
    const std::size_t j = index[axis];
    index[axis] = 0;
    PointSeries& s = by_rest[index];
    if (s.at.empty()) {
      // One other key: the title names it ("..., by KEY") and the legend its values, which leaves the plot its width.
      const bool one_other = plan.axes.size() == 2;
      for (std::size_t k = 0; k < plan.axes.size(); ++k) {
        if (k == axis) continue;
        s.label +=
            (s.label.empty() ? "" : ", ") + (one_other ? "" : plan.axes[k].key + " = ") + plan.axes[k].values[index[k]];
      }
      if (s.label.empty()) s.label = "mean ± sd over the seeds";
    }
    s.at.emplace_back(j, point);
  }
  std::vector<PointSeries> out;
  for (auto& entry : by_rest) out.push_back(std::move(entry.second));
  return out;
}

void setXAxis(monitor::PlotSpec& spec, const XAxis& x) {
  spec.x_label = x.axis->key;
  spec.x_log = x.log;
  if (x.numeric && !x.log) return;
  spec.x_ticks = x.at;
  spec.x_tick_labels = x.axis->values;
  if (!x.numeric) {
    // Half a category beyond the first and the last, so their markers are as far from the frame as from each other.
    spec.x_min = -0.5;
    spec.x_max = static_cast<double>(x.at.size()) - 0.5;
  }
}

}  // namespace swa::study
