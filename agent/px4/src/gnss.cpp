#include "swa/px4/gnss.h"

#include <algorithm>
#include <cmath>

#include "swa/px4/frames.h"

namespace swa::px4 {

namespace {
// A position report this far behind the newest is PX4's clock restarting (a reboot), not a late sample.
constexpr std::uint64_t kRestartUs = 1'000'000;
constexpr std::uint64_t kPeriodSlackUs = 5'000;
}  // namespace

void GnssForward::onGps(const GpsReport& gps) {
  ++counters_.gps_in;
  gps_ = gps;  // the newest by arrival: PX4 sends them in order, and after a reboot its clock starts again
}

std::optional<agent::GnssSample> GnssForward::onLocalPosition(const LocalPositionReport& p) {
  ++counters_.positions_in;
  if (last_position_us_ && p.timestamp_us + kRestartUs < *last_position_us_) {
    ++counters_.clock_restarts;
    last_valid_.reset();
    last_sent_us_ = 0;
  } else if (last_position_us_ && p.timestamp_us <= *last_position_us_) {
    ++counters_.out_of_order;
    return std::nullopt;
  }
  const std::optional<agent::StampNs> stamp = stampNsOf(p.timestamp_us);
  if (!stamp) {
    ++counters_.out_of_order;  // a timestamp beyond SWA's clock range: as unusable as a stale one
    return std::nullopt;
  }
  last_position_us_ = p.timestamp_us;

  bool valid = true;
  if (!gps_ || gps_->fix_type < kGpsFix3d) {
    valid = false;
    ++counters_.no_fix;
  } else if (std::abs(static_cast<double>(p.timestamp_us) - static_cast<double>(gps_->timestamp_us)) * 1e-6 >
             config_.gps_max_age_s) {
    // Either way: a fix from before a clock restart lies far ahead of the new timeline, and is as stale.
    valid = false;
    ++counters_.stale_gps;
  }
  if (!p.xy_valid) {
    valid = false;
    ++counters_.not_xy_valid;
  }
  if (p.dead_reckoning) {
    valid = false;
    ++counters_.dead_reckoning;
  }
  if (!std::isfinite(p.x_m) || !std::isfinite(p.y_m) || !std::isfinite(p.eph_m) || !(p.eph_m > 0.0)) {
    valid = false;
    ++counters_.bad_numbers;
  }

  const bool changed = !last_valid_ || *last_valid_ != valid;
  // A report due at the period is not held back by its own jitter: 5 ms of slack (at 10 Hz from a 10 Hz source every
  // report still goes out).
  const std::uint64_t since_us = p.timestamp_us - std::min(last_sent_us_, p.timestamp_us);
  if (!changed && static_cast<double>(since_us + kPeriodSlackUs) * 1e-6 < config_.min_period_s) return std::nullopt;
  last_valid_ = valid;
  last_sent_us_ = p.timestamp_us;

  agent::GnssSample g;
  g.stamp_ns = *stamp;
  g.valid = valid;
  if (valid) {
    g.position_m = agent::Vec2(p.y_m, p.x_m);  // NED -> east, north
    g.std_m = p.eph_m;
  }
  ++(valid ? counters_.forwarded : counters_.invalid_forwarded);
  return g;
}

}  // namespace swa::px4
