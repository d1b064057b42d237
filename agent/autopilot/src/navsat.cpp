#include "swa/autopilot/navsat.h"

#include <cmath>

namespace swa::ardupilot {
namespace {

constexpr double kSemiMajorM = 6378137.0;            // WGS 84
constexpr double kEccentricity2 = 6.69437999014e-3;  // WGS 84 first eccentricity squared
constexpr double kDegToRad = M_PI / 180.0;

// The radii of curvature at latitude `lat_rad`: meridian (north-south) and prime vertical (east-west).
void radii(double lat_rad, double& meridian_m, double& normal_m) {
  const double s = std::sin(lat_rad);
  const double w = 1.0 - kEccentricity2 * s * s;
  normal_m = kSemiMajorM / std::sqrt(w);
  meridian_m = kSemiMajorM * (1.0 - kEccentricity2) / (w * std::sqrt(w));
}

agent::StampNs stampOf(std::uint64_t timestamp_us) { return static_cast<agent::StampNs>(timestamp_us) * 1000; }

}  // namespace

agent::Vec2 LocalTangent::enuOf(double lat_deg, double lon_deg) const {
  double m = 0.0, n = 0.0;
  radii(origin_lat_deg * kDegToRad, m, n);
  return agent::Vec2((lon_deg - origin_lon_deg) * kDegToRad * n * std::cos(origin_lat_deg * kDegToRad),
                     (lat_deg - origin_lat_deg) * kDegToRad * m);
}

void LocalTangent::latLonOf(const agent::Vec2& enu_m, double& lat_deg, double& lon_deg) const {
  double m = 0.0, n = 0.0;
  radii(origin_lat_deg * kDegToRad, m, n);
  lat_deg = origin_lat_deg + enu_m.y() / m / kDegToRad;
  lon_deg = origin_lon_deg + enu_m.x() / (n * std::cos(origin_lat_deg * kDegToRad)) / kDegToRad;
}

std::optional<agent::GnssSample> NavSatForward::onNavSat(const NavSatReport& r) {
  if (last_us_ && r.timestamp_us < *last_us_) return std::nullopt;
  last_us_ = r.timestamp_us;
  agent::GnssSample g;
  g.stamp_ns = stampOf(r.timestamp_us);
  const bool fix = r.status >= 0 && std::isfinite(r.latitude_deg) && std::isfinite(r.longitude_deg) &&
                   std::abs(r.latitude_deg) < 90.0 && std::abs(r.longitude_deg) <= 180.0;
  if (fix) {
    if (!origin_) origin_ = LocalTangent{r.latitude_deg, r.longitude_deg};
    g.position_m = origin_->enuOf(r.latitude_deg, r.longitude_deg);
    const double variance = 0.5 * (r.variance_east_m2 + r.variance_north_m2);
    g.std_m = r.covariance_type > 0 && std::isfinite(variance) && variance > 0.0 ? std::sqrt(variance)
                                                                                 : config_.unknown_std_m;
    g.valid = true;
  }
  valid_ = g.valid;
  return g;
}

std::optional<agent::GnssSample> NavSatForward::onVehicleTime(std::uint64_t now_us) {
  if (!valid_ || !last_us_ || now_us <= *last_us_) return std::nullopt;
  // At silence_s of silence exactly, not a sample later: the agent's switch is due within silence_s of the last fix.
  if (static_cast<double>(now_us - *last_us_) * 1e-6 < config_.silence_s) return std::nullopt;
  valid_ = false;
  agent::GnssSample g;
  g.stamp_ns = stampOf(now_us);
  return g;
}

}  // namespace swa::ardupilot
