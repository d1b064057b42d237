#include "swa/sim/ardupilot_estimator.h"

namespace swa::sim {
namespace {

constexpr agent::StampNs kPosRetryTimeNoVel = 7'000'000'000;  // AP_NavEKF3.h posRetryTimeNoVel_ms
constexpr agent::StampNs kEkfCheckTime = 1'000'000'000;       // ekf_check.cpp: 10 failing checks at 10 Hz

}  // namespace

ArdupilotEstimator::ArdupilotEstimator(const ArdupilotEstimatorParams& params) : params_(params) {}

void ArdupilotEstimator::gps(agent::StampNs now, bool fix) {
  gps_fix_ = fix;
  if (fix) last_position_ns_ = now;
}

bool ArdupilotEstimator::externalOdometry(agent::StampNs now, agent::StampNs stamp_ns) {
  // With GPS good the active source set is the GPS one; a stamp after the vehicle's clock waits in the buffer.
  if (gps_fix_ || !params_.external_nav || stamp_ns > now) return false;
  last_position_ns_ = now;
  using_external_nav_ = true;
  return true;
}

void ArdupilotEstimator::update(agent::StampNs now) {
  if (gps_fix_) using_external_nav_ = false;
  position_ok_ = last_position_ns_ && now - *last_position_ns_ <= kPosRetryTimeNoVel;
  if (position_ok_) {
    lost_since_ns_.reset();
    ekf_failsafe_ = false;
    return;
  }
  if (!lost_since_ns_) lost_since_ns_ = now;
  if (now - *lost_since_ns_ >= kEkfCheckTime) ekf_failsafe_ = true;
}

}  // namespace swa::sim
