#pragma once
// Internal to the plots (svg_layout.cpp): the tick machinery behind niceTicks, for the axes of one plot.

#include "swa/monitor/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace swa::monitor {

// The finite values seen so far.
struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool empty() const { return lo > hi; }
};

// A tick step mantissa × 10^exponent with the mantissa 1, 2 or 5, kept apart so that multiples are exact decimals.
struct Step {
  int mantissa = 1;
  int exponent = 0;
  double multiple(long long k) const {
    const double m = static_cast<double>(k) * mantissa;
    return exponent < 0 ? m / std::pow(10.0, -exponent) : m * std::pow(10.0, exponent);
  }
  double value() const { return multiple(1); }
  int decimals() const { return std::max(0, -exponent); }
};

// The 1-2-5 step for about `target_ticks` ticks on [lo, hi] (`extend`: the ends may move out to a multiple).
Step stepFor(double lo, double hi, int target_ticks, bool extend);
// The multiples of `step` within [lo, hi], the axis ends at lo and hi.
AxisTicks ticksFromStep(const Step& step, double lo, double hi);

// lo < hi, both finite, not collapsed to one double (a constant series gets a band around its value).
void widenDegenerate(double& lo, double& hi);

// Automatic ticks on [lo, hi] extended to the step, then the forced ends (if any, finite) put back as they are.
AxisTicks axisTicks(Range data, double forced_lo, double forced_hi, bool include_zero, int target_ticks);

}  // namespace swa::monitor
