#pragma once
// Formation control (paper §III-D with the sign erratum of DESIGN §3.5): v_d = -k_p p - k_v v drives the UAV to
// the floating-frame origin. The paper's e = -x with v_d = -k e is positive feedback and diverges.

#include <algorithm>
#include <cmath>

#include "swa/agent/config.h"
#include "swa/agent/geometry.h"

namespace swa::agent {

inline Vec2 formationVelocity(const Vec2& position, const Vec2& velocity, const ControlConfig& c) {
  return -c.k_p * position - c.k_v * velocity;
}

// Scales the vector down to |v| <= v_max keeping its direction; anything non-finite becomes a hover command. The
// scaled vector's norm can round one step above v_max, so it is scaled again by the next smaller factor until it
// is not (at most a few steps).
inline Vec2 saturate(const Vec2& v, double v_max) {
  if (!isFinite(v)) return Vec2::Zero();
  const double n = v.norm();
  if (n <= v_max) return v;
  double factor = v_max / n;
  Vec2 out = v * factor;
  while (out.norm() > v_max && factor > 0.0) {
    factor = std::nextafter(factor, 0.0);
    out = v * factor;
  }
  return out;
}

// Heading control (ControlConfig: facing_deg): the yaw rate that turns the sensor's axis to the common facing
// direction `facing_deg` (counter-clockwise from east; a mission's direction of travel while it moves, else
// ControlConfig::facing_deg). Exactly 0 with an all-round sensor, so such an agent never touches its heading. Always
// finite and within +-max_yaw_rate_radps, whatever the heading (a non-finite heading or direction gives 0).
inline double headingRate(double heading_rad, const SensorConfig& sensor, const ControlConfig& c, double facing_deg) {
  if (sensor.fov_deg >= 360.0 || !std::isfinite(heading_rad)) return 0.0;
  constexpr double kRadPerDeg = M_PI / 180.0;
  const double wanted = (facing_deg - sensor.mount_deg) * kRadPerDeg;
  const double error = std::remainder(wanted - heading_rad, 2.0 * M_PI);  // in [-pi, pi]: the shorter way round
  const double rate = c.k_yaw * error;
  if (!std::isfinite(rate)) return 0.0;
  return std::clamp(rate, -c.max_yaw_rate_radps, c.max_yaw_rate_radps);
}

inline double headingRate(double heading_rad, const SensorConfig& sensor, const ControlConfig& c) {
  return headingRate(heading_rad, sensor, c, c.facing_deg);
}

}  // namespace swa::agent
