#include "swa/autopilot/odometry_feed.h"

#include <cmath>

namespace swa::autopilot {
namespace {

// In whole nanoseconds as doubles (exact below 2^53 ns, 104 days): 0.3 s is 300 000 000 ns, not 0.30000000000000004 s
// of a product, and no int64 subtraction overflows on a stamp off the wire.
double ageNs(agent::StampNs now, agent::StampNs stamp) { return static_cast<double>(now) - static_cast<double>(stamp); }

}  // namespace

double OdometryFeed::staleNs() const { return std::round(config_.stale_after_s * 1e9); }

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
  if (!(std::fabs(ageNs(vehicle_now_ns, s.stamp_ns)) <=
        staleNs())) {  // NaN-safe; a state from the future is no fresher
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
  last_sent_ns_ = s.stamp_ns;
  return o;
}

bool OdometryFeed::expire(agent::StampNs vehicle_now_ns) {
  if (!feeding_) return false;
  if (ageNs(vehicle_now_ns, last_sent_ns_) <= staleNs()) return false;
  feeding_ = false;
  ++counters_.silences;
  return true;
}

}  // namespace swa::autopilot
