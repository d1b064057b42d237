// Axis ticks of the report's plots: 1-2-5 steps whose multiples are exact decimals, and how their labels are written.

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <system_error>

#include "svg_ticks.h"

namespace swa::monitor {
namespace {

constexpr double kTolerance = 1e-9;  // relative slack when snapping to 1-2-5 steps and tick multiples
constexpr long long kMaxTicks = 1000;
// A log axis spans at least a factor 3 (log10 3 decades): any such range holds two of 1..9 × 10^k, so it has ticks.
const double kMinLogSpan = std::log10(3.0);
// Room beside the extreme points of a log axis, as a fraction of its decades (a marker on the edge stays whole).
constexpr double kLogPad = 0.05;

Step next(Step s) {
  if (s.mantissa == 1) return {2, s.exponent};
  if (s.mantissa == 2) return {5, s.exponent};
  return {1, s.exponent + 1};
}

Step previous(Step s) {
  if (s.mantissa == 5) return {2, s.exponent};
  if (s.mantissa == 2) return {1, s.exponent};
  return {5, s.exponent - 1};
}

// span / (target - 1) rounded up to the 1-2-5 sequence.
Step roundedUp(double span, int target_ticks) {
  const double raw = span / std::max(1, target_ticks - 1);
  if (!(raw > 0.0) || !std::isfinite(raw)) return Step{};
  int exponent = static_cast<int>(std::floor(std::log10(raw)));
  const double norm = exponent < 0 ? raw * std::pow(10.0, -exponent) : raw / std::pow(10.0, exponent);
  int mantissa = 10;
  if (norm <= 1.0 + kTolerance) {
    mantissa = 1;
  } else if (norm <= 2.0 + kTolerance) {
    mantissa = 2;
  } else if (norm <= 5.0 + kTolerance) {
    mantissa = 5;
  }
  if (mantissa == 10) {
    mantissa = 1;
    ++exponent;
  }
  return Step{mantissa, exponent};
}

// How many ticks `step` gives on [lo, hi]: with the range extended outwards to multiples of the step, or only the
// multiples inside it.
long long tickCount(const Step& step, double lo, double hi, bool extend) {
  const double s = step.value();
  if (extend) {
    return static_cast<long long>(std::ceil(hi / s - kTolerance)) -
           static_cast<long long>(std::floor(lo / s + kTolerance)) + 1;
  }
  return static_cast<long long>(std::floor(hi / s + kTolerance)) -
         static_cast<long long>(std::ceil(lo / s - kTolerance)) + 1;
}

// Ticks at the multiples of `step` inside [lo, hi] (with a little slack so an end on a multiple counts).
std::vector<double> multiplesWithin(const Step& step, double lo, double hi) {
  const double s = step.value();
  const long long first = static_cast<long long>(std::ceil(lo / s - kTolerance));
  const long long last = static_cast<long long>(std::floor(hi / s + kTolerance));
  std::vector<double> values;
  for (long long k = first; k <= last && k - first < kMaxTicks; ++k) values.push_back(step.multiple(k));
  return values;
}

}  // namespace

// The step of the 1-2-5 sequence whose tick count on [lo, hi] is closest to the target. Ties: with an extended range
// the one that wastes less of it, else the larger step (fewer labels). Candidates: the rounded-up step and its
// neighbours (two smaller, one larger).
Step stepFor(double lo, double hi, int target_ticks, bool extend) {
  const Step up = roundedUp(hi - lo, target_ticks);
  const std::array<Step, 4> candidates{next(up), up, previous(up), previous(previous(up))};
  const auto error = [&](const Step& c) { return std::llabs(tickCount(c, lo, hi, extend) - target_ticks); };
  const auto shown = [&](const Step& c) { return static_cast<double>(tickCount(c, lo, hi, true) - 1) * c.value(); };
  Step best = candidates.front();
  for (const Step& c : candidates) {
    const long long e = error(c);
    const long long b = error(best);
    if (e < b || (e == b && extend && shown(c) < shown(best))) best = c;
  }
  return best;
}

AxisTicks ticksFromStep(const Step& step, double lo, double hi) {
  AxisTicks t;
  t.lo = lo;
  t.hi = hi;
  t.step = step.value();
  t.decimals = step.decimals();
  t.values = multiplesWithin(step, lo, hi);
  return t;
}

// lo < hi, both finite, not collapsed to one double.
void widenDegenerate(double& lo, double& hi) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) {
    lo = 0.0;
    hi = 1.0;
    return;
  }
  if (lo > hi) std::swap(lo, hi);
  const double scale = std::max(std::fabs(lo), std::fabs(hi));
  if (hi - lo <= 1e-12 * scale || hi == lo) {
    const double d = scale > 0.0 ? 0.1 * scale : 1.0;
    lo -= d;
    hi += d;
  }
}

// Automatic ticks on [lo, hi] extended to the step, then the forced ends (if any) put back as they are.
AxisTicks axisTicks(Range data, double forced_lo, double forced_hi, bool include_zero, int target_ticks) {
  if (include_zero) {
    data.add(0.0);
  }
  double lo = data.empty() ? 0.0 : data.lo;
  double hi = data.empty() ? 1.0 : data.hi;
  const bool has_lo = std::isfinite(forced_lo);
  const bool has_hi = std::isfinite(forced_hi);
  if (has_lo) lo = forced_lo;
  if (has_hi) hi = forced_hi;
  if (has_lo && !has_hi && !(hi > lo)) hi = lo + std::max(1.0, 0.1 * std::fabs(lo));
  if (has_hi && !has_lo && !(lo < hi)) lo = hi - std::max(1.0, 0.1 * std::fabs(hi));
  widenDegenerate(lo, hi);
  AxisTicks t = niceTicks(lo, hi, target_ticks);
  if (has_lo || has_hi) {
    if (has_lo) t.lo = forced_lo;
    if (has_hi) t.hi = forced_hi;
    t = ticksFromStep(stepFor(t.lo, t.hi, target_ticks, false), t.lo, t.hi);
  }
  return t;
}

std::string formatFixed(double value, int decimals) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  std::array<char, 64> buf{};
  if (std::fabs(value) >= 1e15) {
    const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), value);
    return r.ec == std::errc() ? std::string(buf.data(), r.ptr) : std::string("nan");
  }
  const auto r =
      std::to_chars(buf.data(), buf.data() + buf.size(), value, std::chars_format::fixed, std::clamp(decimals, 0, 17));
  if (r.ec != std::errc()) return "nan";  // cannot happen below 1e15 with 64 chars
  std::string s(buf.data(), r.ptr);
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  if (s == "-0") s = "0";
  return s;
}

double niceStep(double span, int target_ticks) { return stepFor(0.0, span, target_ticks, true).value(); }

AxisTicks niceTicks(double lo, double hi, int target_ticks) {
  widenDegenerate(lo, hi);
  const Step step = stepFor(lo, hi, target_ticks, true);
  const double s = step.value();
  const long long first = static_cast<long long>(std::floor(lo / s + kTolerance));
  const long long last = static_cast<long long>(std::ceil(hi / s - kTolerance));
  return ticksFromStep(step, step.multiple(first), step.multiple(last));
}

std::string formatTick(double value, const AxisTicks& ticks) {
  if (ticks.log && value > 0.0) {
    // 0.05 needs 2 decimals, 20 none: the decimals of the value's own power of ten.
    return formatFixed(value, std::max(0, -static_cast<int>(std::floor(std::log10(value) + kTolerance))));
  }
  return formatFixed(value, ticks.decimals);
}

double AxisTicks::fraction(double value) const {
  if (!log) return (value - lo) / (hi - lo);
  if (!(value > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return (std::log10(value) - std::log10(lo)) / (std::log10(hi) - std::log10(lo));
}

AxisTicks logTicks(double lo, double hi, int target_ticks) {
  if (!(lo > 0.0) || !(hi > 0.0) || !std::isfinite(lo) || !std::isfinite(hi)) {
    lo = 1.0;
    hi = 10.0;
  }
  if (lo > hi) std::swap(lo, hi);
  double a = std::log10(lo);
  double b = std::log10(hi);
  if (b - a < kMinLogSpan) {
    const double mid = 0.5 * (a + b);
    a = mid - 0.5 * kMinLogSpan;
    b = mid + 0.5 * kMinLogSpan;
  }
  const double pad = kLogPad * (b - a);
  AxisTicks t;
  t.log = true;
  t.step = 0.0;
  t.lo = std::pow(10.0, a - pad);
  t.hi = std::pow(10.0, b + pad);
  // The first mantissa set with enough ticks inside; 1..9 always has 2 in a factor-3 range.
  static const std::array<std::vector<int>, 3> kMantissas{std::vector<int>{1}, std::vector<int>{1, 2, 5},
                                                          std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9}};
  constexpr std::size_t kEnoughTicks = 3;
  for (const std::vector<int>& mantissas : kMantissas) {
    t.values.clear();
    for (int e = static_cast<int>(std::floor(a - pad)) - 1; e <= static_cast<int>(std::ceil(b + pad)); ++e) {
      for (const int m : mantissas) {
        const double v = Step{m, e}.value();
        if (v >= t.lo * (1.0 - kTolerance) && v <= t.hi * (1.0 + kTolerance)) t.values.push_back(v);
      }
    }
    if (t.values.size() >= kEnoughTicks) break;
  }
  // Many decades: every k-th power of ten, so the labels do not run into each other.
  const std::size_t most = 2 * static_cast<std::size_t>(std::max(target_ticks, 1));
  if (t.values.size() > most) {
    const std::size_t every = (t.values.size() + most - 1) / most;
    std::vector<double> kept;
    for (std::size_t i = 0; i < t.values.size(); i += every) kept.push_back(t.values[i]);
    t.values = std::move(kept);
  }
  t.decimals = t.values.empty() ? 0 : std::max(0, -static_cast<int>(std::floor(std::log10(t.values.front()))));
  return t;
}

}  // namespace swa::monitor
