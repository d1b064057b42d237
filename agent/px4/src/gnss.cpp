#include "swa/px4/gnss.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "swa/px4/frames.h"

namespace swa::px4 {

namespace {
// A position report this far behind the newest is PX4's clock restarting (a reboot), not a late sample.
constexpr std::uint64_t kRestartUs = 1'000'000;
constexpr std::uint64_t kPeriodSlackUs = 5'000;

bool samePlace(const GeoPoint& a, const GeoPoint& b) { return a.lat_deg == b.lat_deg && a.lon_deg == b.lon_deg; }

// Metres to the centimetre for the log, without a "-0.00" for a hair south of due east.
double centimetres(double m) { return std::round(m * 100.0) / 100.0 + 0.0; }

}  // namespace

// Why per report: EKF2 publishes the new ref_timestamp, ref_lat and ref_lon in the same vehicle_local_position as the
// x, y it re-based on them (both come from one estimator state in PublishLocalPosition), so every report names its
// own frame. Undoing the change report by report is exact from the first re-based report on; there is no period in
// which x, y have moved and the reference has not, or the other way round, to guess about.
std::optional<NedPoint> GnssForward::inFirstFrame(const LocalPositionReport& p) {
  const NedPoint raw{p.x_m, p.y_m};
  const GeoPoint reference{p.ref_lat_deg, p.ref_lon_deg};
  const bool usable = p.xy_global && isProjectionReference(reference);
  if (!first_) {
    // Nothing to bring x, y into yet: the first reference's frame is PX4's frame as it is.
    if (usable) first_ = current_ = Origin{p.ref_timestamp_us, MapProjection(reference)};
    return raw;
  }
  if (!usable) {
    ++counters_.unusable_reference;
    if (!std::exchange(reference_lost_, true)) {
      events_.emplace_back(
          "PX4's local position has no usable global reference (xy_global false, or ref_lat / ref_lon not a place) "
          "after it had one: GNSS forwarded as lost until it has one again");
    }
    return std::nullopt;
  }
  reference_lost_ = false;
  if (p.ref_timestamp_us != current_->ref_timestamp_us || !samePlace(reference, current_->projection.reference())) {
    onOriginChange(p);
  }
  // At the first origin's place (a re-set that did not move it) x, y are already in its frame: not one rounding more.
  if (samePlace(reference, first_->projection.reference())) return raw;
  return first_->projection.project(current_->projection.reproject(raw));
}

void GnssForward::onOriginChange(const LocalPositionReport& p) {
  const std::uint64_t from_us = current_->ref_timestamp_us;
  current_ = Origin{p.ref_timestamp_us, MapProjection(GeoPoint{p.ref_lat_deg, p.ref_lon_deg})};
  ++counters_.origin_changes;
  const NedPoint moved = first_->projection.project(current_->projection.reference());
  char text[256];
  std::snprintf(text, sizeof text,
                "PX4 moved its local origin (ref_timestamp %llu -> %llu, %.2f m east, %.2f m north of the first): "
                "positions brought into the first origin's frame",
                static_cast<unsigned long long>(from_us), static_cast<unsigned long long>(p.ref_timestamp_us),
                centimetres(moved.east_m), centimetres(moved.north_m));
  events_.emplace_back(text);
}

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
    // The first origin stays: a reference is a place on the ground, so a rebooted PX4's new origin is brought back to
    // it like any other change, and the agent's frame does not jump across the reboot either.
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
  // Every report, whether it goes out or not: a change of origin is noticed (and counted) when it happens.
  const std::optional<NedPoint> position = inFirstFrame(p);

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
  } else if (!position) {
    valid = false;  // counted by inFirstFrame
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
    g.position_m = agent::Vec2(position->east_m, position->north_m);  // NED -> east, north
    g.std_m = p.eph_m;
  }
  ++(valid ? counters_.forwarded : counters_.invalid_forwarded);
  return g;
}

}  // namespace swa::px4
