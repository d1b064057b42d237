#include "swa/px4/frames.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace swa::px4 {
namespace {
constexpr double kPi = 3.14159265358979323846;
}

bool isAttitude(const Quaternion& q) {
  if (!std::isfinite(q.w) || !std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) return false;
  const double norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return std::abs(norm - 1.0) <= kNormTolerance;
}

Euler eulerOf(const Quaternion& q) {
  // Through the rotation matrix, as PX4's matrix::Euler does, including its treatment of the singularity: within
  // 1e-3 rad of |pitch| = 90 deg roll and yaw turn about the same axis, roll is taken as 0 and the rest is yaw.
  const double r02 = 2.0 * (q.x * q.z + q.w * q.y);
  const double r12 = 2.0 * (q.y * q.z - q.w * q.x);
  const double r20 = 2.0 * (q.x * q.z - q.w * q.y);
  Euler e;
  e.pitch = std::asin(std::clamp(-r20, -1.0, 1.0));  // rounding can take it a hair beyond +-1: asin would be NaN
  if (std::abs(e.pitch - kPi / 2) < 1e-3) {
    e.yaw = std::atan2(r12, r02);
  } else if (std::abs(e.pitch + kPi / 2) < 1e-3) {
    e.yaw = std::atan2(-r12, -r02);
  } else {
    e.roll = std::atan2(2.0 * (q.y * q.z + q.w * q.x), 1.0 - 2.0 * (q.x * q.x + q.y * q.y));
    e.yaw = std::atan2(2.0 * (q.x * q.y + q.w * q.z), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
  }
  return e;
}

Quaternion quaternionOf(const Euler& e) {
  const double cr = std::cos(e.roll / 2), sr = std::sin(e.roll / 2);
  const double cp = std::cos(e.pitch / 2), sp = std::sin(e.pitch / 2);
  const double cy = std::cos(e.yaw / 2), sy = std::sin(e.yaw / 2);
  return {cr * cp * cy + sr * sp * sy, sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
          cr * cp * sy - sr * sp * cy};
}

double wrapPi(double angle_rad) {
  double a = std::remainder(angle_rad, 2.0 * kPi);  // in [-pi, pi]
  if (a <= -kPi) a += 2.0 * kPi;
  return a;
}

SwaAttitude swaAttitude(const Euler& e) { return {-e.roll, -e.pitch, wrapPi(kPi / 2 - e.yaw)}; }

Euler px4Euler(const SwaAttitude& a) { return {-a.roll_rad, -a.pitch_rad, wrapPi(kPi / 2 - a.heading_rad)}; }

NedVelocity nedOf(const agent::Vec2& stable_mps) { return {stable_mps.y(), stable_mps.x(), 0.0}; }

agent::Vec2 stableOf(const NedVelocity& ned) { return {ned.east, ned.north}; }

double yawspeedOf(double yaw_rate_radps) { return -yaw_rate_radps; }

double yawRateOf(double yawspeed_radps) { return -yawspeed_radps; }

std::optional<agent::StampNs> stampNsOf(std::uint64_t timestamp_us) {
  constexpr std::uint64_t kMaxUs = static_cast<std::uint64_t>(std::numeric_limits<agent::StampNs>::max()) / 1000;
  if (timestamp_us > kMaxUs) return std::nullopt;
  return static_cast<agent::StampNs>(timestamp_us) * 1000;
}

std::optional<std::uint64_t> timestampUsOf(agent::StampNs stamp_ns) {
  if (stamp_ns < 0) return std::nullopt;
  return static_cast<std::uint64_t>(stamp_ns / 1000);
}

}  // namespace swa::px4
