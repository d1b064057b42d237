#include "swa/autopilot/odometry_feed.h"

#include <cmath>

namespace swa::autopilot {

OdometryFeed::OdometryFeed(const OdometryFeedConfig& config) : config_(config) {}

std::optional<Odometry> OdometryFeed::onState(const agent::Diagnostics& s, agent::StampNs vehicle_now_ns) {
  // A reset: tracking again after not tracking, or the agent's timeline restarted. Counted whether or not this state
  // is sent, so that the first one sent after it carries it.
  const bool tracking = s.stage == agent::Stage::kTracking;
  const bool resynced = resyncs_ && s.stamp_resyncs != *resyncs_;
  if ((tracking && !was_tracking_) || resynced) {
    ++reset_counter_;
    ++counters_.resets;
  }
  was_tracking_ = tracking;
  resyncs_ = s.stamp_resyncs;

  feeding_ = false;
  if (config_.mode == OdometryMode::kOff || (config_.mode == OdometryMode::kWhileGnssLost && s.gnss_valid)) {
    ++counters_.skipped_gnss;
    return std::nullopt;
  }
  const double age_s = static_cast<double>(vehicle_now_ns - s.stamp_ns) * 1e-9;
  if (!(std::fabs(age_s) <= config_.stale_after_s)) {  // NaN-safe; a state from the future is no fresher
    ++counters_.skipped_stale;
    return std::nullopt;
  }
  const bool finite = agent::isFinite(s.position_m) && agent::isFinite(s.velocity_mps) &&
                      s.position_cov_m2.allFinite() && s.velocity_cov_m2ps2.allFinite();
  const double max_var = config_.max_position_std_m * config_.max_position_std_m;
  if (!tracking || !finite || s.position_cov_m2(0, 0) > max_var || s.position_cov_m2(1, 1) > max_var ||
      s.position_cov_m2(0, 0) < 0.0 || s.position_cov_m2(1, 1) < 0.0 || s.velocity_cov_m2ps2(0, 0) < 0.0 ||
      s.velocity_cov_m2ps2(1, 1) < 0.0) {
    ++counters_.skipped_invalid;
    return std::nullopt;
  }
  Odometry o;
  o.stamp_ns = s.stamp_ns;
  o.position_m = s.position_m;
  o.velocity_mps = s.velocity_mps;
  o.position_var_m2 = s.position_cov_m2.diagonal();
  o.velocity_var_m2ps2 = s.velocity_cov_m2ps2.diagonal();
  o.reset_counter = reset_counter_;
  ++counters_.sent;
  feeding_ = true;
  return o;
}

}  // namespace swa::autopilot
