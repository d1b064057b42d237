#pragma once
// GNSS and the localisation-loss signal from the vehicle (issue #27): PX4's vehicle_gps_position (SensorGps) and
// vehicle_local_position turned into SWA's GNSS samples, so that an agent on a real vehicle stops using GNSS the
// moment its autopilot says it has no fix or no valid horizontal position, and uses it again when both are back.
// Pure: no DDS; the bridge feeds it the messages' fields, the tests feed it anything.
//
// A sample is valid only if the newest GPS report (at most `gps_max_age_s` from the position, on PX4's clock) has a
// 3D fix or better, the position says xy_valid and not dead_reckoning (PX4 keeps xy_valid while it dead-reckons, e.g.
// after rejecting a jammed receiver that still reports a fix), and x, y and eph are finite with eph > 0. Anything else
// is a valid=false sample ("no fix"), never a dropped one: the agent must hear the loss. The position is PX4's local
// NED frame turned to SWA's (x east = y_NED, y north = x_NED); its origin is the vehicle's own EKF origin, which is
// all the agent needs (it holds positions relative to its first fix). std_m is PX4's eph.
//
// That origin can move in flight (issue #46): EKF2 re-sets its global origin (a new GPS origin, a
// SET_GPS_GLOBAL_ORIGIN command, a reboot) and re-bases x, y on it, so x, y jump by the origins' difference. The first
// usable reference (xy_global with a finite ref_lat, ref_lon) is kept; a report with another one (ref_timestamp,
// ref_lat or ref_lon changed) has its x, y brought into the first origin's frame through PX4's own map projection
// (map_projection.h): the agent sees no jump. Each change is counted and reported once (takeEvents). Once a first
// origin is known, a report without a usable reference cannot be placed: it goes out as no fix, never as a jump.
// Before any reference PX4's local frame is forwarded as it is (a vehicle without a global origin, as before #46).

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "swa/agent/samples.h"
#include "swa/px4/map_projection.h"

namespace swa::px4 {

struct GpsReport {
  std::uint64_t timestamp_us = 0;
  std::uint8_t fix_type = 0;  // 0-1 none, 2 2D, 3 3D, 4 DGPS, 5 RTK float, 6 RTK fixed
};

struct LocalPositionReport {
  std::uint64_t timestamp_us = 0;
  bool xy_valid = false;
  bool dead_reckoning = false;  // the estimator runs on inertial data alone (no position aiding)
  double x_m = 0.0, y_m = 0.0;  // NED
  double eph_m = 0.0;
  // The global reference x, y are relative to: valid with xy_global; ref_timestamp is when PX4 set it (its clock).
  bool xy_global = false;
  std::uint64_t ref_timestamp_us = 0;
  double ref_lat_deg = 0.0, ref_lon_deg = 0.0;
};

struct GnssForwardConfig {
  double gps_max_age_s = 1.0;  // PX4 sends vehicle_gps_position at 5-10 Hz: older means the receiver went quiet
  double min_period_s = 0.1;   // valid samples at most at 10 Hz (the agent's GNSS rate); a change of validity at once
};

struct GnssForwardCounters {
  std::uint64_t positions_in = 0, gps_in = 0, forwarded = 0, invalid_forwarded = 0;
  std::uint64_t no_fix = 0, not_xy_valid = 0, dead_reckoning = 0, bad_numbers = 0, stale_gps = 0;  // why not valid
  std::uint64_t out_of_order = 0;        // position reports dropped: not newer than the last one
  std::uint64_t clock_restarts = 0;      // PX4's clock went back by more than a second (a reboot): started afresh
  std::uint64_t origin_changes = 0;      // PX4 moved its local origin: positions brought into the first origin's frame
  std::uint64_t unusable_reference = 0;  // no usable reference after a first one: not valid (why not valid, too)
};

constexpr std::uint8_t kGpsFix3d = 3;

class GnssForward {
 public:
  explicit GnssForward(const GnssForwardConfig& config = {}) : config_(config) {}

  void onGps(const GpsReport& gps);
  // The GNSS sample to forward for this position report, if any (rate-limited while the validity does not change).
  std::optional<agent::GnssSample> onLocalPosition(const LocalPositionReport& position);

  const GnssForwardCounters& counters() const { return counters_; }
  // What happened to the local origin since the last call, for the log: each origin change and each loss of a usable
  // reference, once.
  std::vector<std::string> takeEvents() { return std::exchange(events_, {}); }

 private:
  struct Origin {
    std::uint64_t ref_timestamp_us = 0;
    MapProjection projection;
  };

  // The report's position (NED) in the first origin's frame; nullopt if it cannot be placed there.
  std::optional<NedPoint> inFirstFrame(const LocalPositionReport& p);
  void onOriginChange(const LocalPositionReport& p);

  GnssForwardConfig config_;
  GnssForwardCounters counters_;
  std::optional<Origin> first_, current_;  // the first usable reference, and the newest one
  bool reference_lost_ = false;            // reported, until a usable reference returns
  std::vector<std::string> events_;
  std::optional<GpsReport> gps_;
  std::optional<std::uint64_t> last_position_us_;
  std::optional<bool> last_valid_;
  std::uint64_t last_sent_us_ = 0;
};

}  // namespace swa::px4
