#include "swa/sim/px4_estimator.h"

#include <cmath>

namespace swa::sim {
namespace {

constexpr agent::StampNs kSecond = 1'000'000'000;
constexpr agent::StampNs kNoAidTimeoutMax = kSecond;    // common.h no_aid_timeout_max
constexpr agent::StampNs kEvMaxInterval = 200'000'000;  // common.h EV_MAX_INTERVAL
constexpr int kEvCtrlHorizontalPosition = 1 << 0;
constexpr int kEvCtrlVelocity = 1 << 2;

}  // namespace

Px4Estimator::Px4Estimator(const Px4EstimatorParams& params) : params_(params) {}

bool Px4Estimator::visionFusable(bool position, bool velocity) const {
  return (position && (params_.ev_ctrl & kEvCtrlHorizontalPosition) != 0) ||
         (velocity && (params_.ev_ctrl & kEvCtrlVelocity) != 0);
}

void Px4Estimator::gnss(agent::StampNs now, bool fix) {
  if (fix) last_gnss_ns_ = now;
}

void Px4Estimator::externalVision(agent::StampNs now, bool position, bool velocity) {
  if (!visionFusable(position, velocity)) return;
  // Starting needs two samples in a row less than EV_MAX_INTERVAL apart (ev_control.cpp).
  if (last_ev_ns_ && now - *last_ev_ns_ < kEvMaxInterval) ev_active_ = true;
  last_ev_ns_ = now;
}

void Px4Estimator::update(agent::StampNs now) {
  if (ev_active_ && (!last_ev_ns_ || now - *last_ev_ns_ > 2 * kEvMaxInterval)) ev_active_ = false;
  const bool gnss_recent = last_gnss_ns_ && now - *last_gnss_ns_ <= kNoAidTimeoutMax;
  aided_ = gnss_recent || ev_active_;
  if (aided_) aided_timer_ns_ = now - kNoAidTimeoutMax;
  const auto timeout = static_cast<agent::StampNs>(std::llround(params_.noaid_tout_s * 1e9));
  xy_valid_ = aided_timer_ns_ && now - *aided_timer_ns_ <= timeout;
}

}  // namespace swa::sim
