#include "swa/agent/imu_bias.h"

#include <algorithm>

namespace swa::agent {
namespace {

// The mean's gain is dt / max(1 s, t): the first second is an exponential average, not a single sample's value.
constexpr double kMinAveragingS = 1.0;

}  // namespace

ImuBiasRemover::ImuBiasRemover(double window_s, double freeze_speed_mps, double freeze_hold_s)
    : window_s_(window_s), freeze_speed_mps_(freeze_speed_mps), freeze_hold_s_(freeze_hold_s) {}

void ImuBiasRemover::reset() {
  bias_.setZero();
  averaged_s_ = 0.0;
  started_ = false;
  frozen_ = false;
  seen_fast_ = false;
}

Vec2 ImuBiasRemover::correct(const Vec2& a, StampNs stamp, const Vec2& command_mps) {
  if (!enabled()) return a;
  if (!started_) {
    started_ = true;
    last_ns_ = stamp;
    return a - bias_;
  }
  if (stamp <= last_ns_) return a - bias_;
  const double dt = secondsBetween(last_ns_, stamp);
  last_ns_ = stamp;
  if (command_mps.norm() > freeze_speed_mps_) {
    seen_fast_ = true;
    last_fast_ns_ = stamp;
  }
  frozen_ = seen_fast_ && secondsBetween(last_fast_ns_, stamp) <= freeze_hold_s_;
  if (!frozen_) {
    averaged_s_ += dt;
    const double horizon = std::min(window_s_, std::max(kMinAveragingS, averaged_s_));
    bias_ += (a - bias_) * std::min(1.0, dt / horizon);
  }
  return a - bias_;
}

}  // namespace swa::agent
