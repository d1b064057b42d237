#pragma once
// Shared by the world tests (test_world_*.cpp): a calm scenario, in which only what a test turns on happens.

#include <cstdint>
#include <limits>

#include "swa/sim/scenario.h"

namespace swa::sim::testing {

// `n` UAVs exactly at their lattice slots (no jitter), all heading east, no wind, GNSS never lost; the sensors as the
// defaults have them.
inline Scenario calmScenario(int n, std::uint64_t seed) {
  Scenario s;
  s.uav_count = n;
  s.seed = seed;
  s.formation.position_jitter_m = 0.0;
  s.dynamics.heading = HeadingMode::kZero;
  s.wind.gust_std = 0.0;
  s.wind.common_std = 0.0;
  s.gnss.dropout_start_s = std::numeric_limits<double>::infinity();
  return s;
}

// An IMU without any error: no tilt or accelerometer bias or noise, an ideal compass, a perfect attitude.
inline ImuSetup exactImu(ImuSetup setup = {}) {
  setup.noise_std = 0.0;
  setup.bias_std = 0.0;
  setup.heading_noise_std_rad = 0.0;
  setup.attitude_error_std_rad = 0.0;
  setup.accel_bias_std_mps2 = 0.0;
  setup.accel_noise_std_mps2 = 0.0;
  return setup;
}

// No IMU, MPS or GNSS sample at all, for a test of the dynamics alone.
inline void sensorsOff(Scenario& s) {
  s.imu.rate_hz = 0.0;
  s.mps.rate_hz = 0.0;
  s.gnss.rate_hz = 0.0;
}

}  // namespace swa::sim::testing
