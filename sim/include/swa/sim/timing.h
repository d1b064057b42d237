#pragma once
// Sim time is integer nanoseconds: step k of a world running at rate f is stamped k * round(1e9 / f), so stamps never
// accumulate floating-point error and every component agrees on them bit for bit.
//
// Sensors run on the dynamics clock: a sensor at rate f_s samples on the steps where k % round(f_dyn / f_s) == 0.
// Sensor rates must therefore divide the dynamics rate (the scenario loader checks it); a rate that does not is
// rounded to the nearest whole number of steps, a rate above the dynamics rate samples every step, and a rate <= 0
// (or not finite) switches the sensor off.

#include <cmath>
#include <cstdint>
#include <limits>

#include "swa/agent/samples.h"

namespace swa::sim {

inline agent::StampNs stepPeriodNs(double rate_hz) { return std::llround(1e9 / rate_hz); }

// 0 means "never sample".
inline std::int64_t sensorPeriodSteps(double sensor_rate_hz, double dynamics_rate_hz) {
  if (!(sensor_rate_hz > 0.0) || !std::isfinite(sensor_rate_hz)) return 0;
  const std::int64_t period = std::llround(dynamics_rate_hz / sensor_rate_hz);
  return period < 1 ? 1 : period;
}

inline bool sensorDue(std::int64_t step_index, std::int64_t period_steps) {
  return period_steps > 0 && step_index % period_steps == 0;
}

// Seconds to nanoseconds for durations; +inf (and anything beyond ~292 years) saturates to "never".
inline agent::StampNs durationNs(double seconds) {
  constexpr double kMaxSeconds = 9.2e9;
  if (!(seconds < kMaxSeconds)) return std::numeric_limits<agent::StampNs>::max();
  return std::llround(seconds * 1e9);
}

inline double stampSeconds(agent::StampNs stamp_ns) { return static_cast<double>(stamp_ns) / 1e9; }

// Angle in (-pi, pi].
inline double wrapAngle(double angle_rad) {
  const double wrapped = std::remainder(angle_rad, 2.0 * M_PI);
  return wrapped <= -M_PI ? wrapped + 2.0 * M_PI : wrapped;
}

}  // namespace swa::sim
