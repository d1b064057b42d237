#include "swa/px4/map_projection.h"

#include <algorithm>
#include <cmath>

namespace swa::px4 {
namespace {

constexpr double kEarthRadiusM = 6371000.0;  // PX4's CONSTANTS_RADIUS_OF_EARTH
constexpr double kDegToRad = M_PI / 180.0;

// A longitude difference in (-180, 180] degrees, taken in degrees: the difference of two nearby longitudes keeps its
// digits, where the difference of their radians would not.
double lonDifferenceDeg(double lon_deg, double ref_lon_deg) {
  const double d = std::remainder(lon_deg - ref_lon_deg, 360.0);
  return d == -180.0 ? 180.0 : d;
}

}  // namespace

bool isProjectionReference(const GeoPoint& p) {
  return std::isfinite(p.lat_deg) && std::isfinite(p.lon_deg) && std::abs(p.lat_deg) < 90.0 &&
         std::abs(p.lon_deg) <= 180.0;
}

MapProjection::MapProjection(const GeoPoint& reference)
    : reference_(reference),
      sin_lat_(std::sin(reference.lat_deg * kDegToRad)),
      cos_lat_(std::cos(reference.lat_deg * kDegToRad)) {}

NedPoint MapProjection::project(const GeoPoint& p) const {
  const double d_lat = (p.lat_deg - reference_.lat_deg) * kDegToRad;
  const double d_lon = lonDifferenceDeg(p.lon_deg, reference_.lon_deg) * kDegToRad;
  const double cos_lat = std::cos(p.lat_deg * kDegToRad);
  const double half = std::sin(0.5 * d_lon);
  // PX4's cos(lat0) sin(lat) - sin(lat0) cos(lat) cos(dlon) and its great-circle cosine, rewritten with the half-angle
  // so that nothing near 1 is subtracted from 1: the bearing's parts scaled by sin(c), and cos(c).
  const double north = std::sin(d_lat) + 2.0 * sin_lat_ * cos_lat * half * half;
  const double east = cos_lat * std::sin(d_lon);
  const double cos_c = std::cos(d_lat) - 2.0 * cos_lat_ * cos_lat * half * half;
  const double sin_c = std::hypot(north, east);
  if (sin_c == 0.0) return {};
  const double scale = std::atan2(sin_c, cos_c) / sin_c * kEarthRadiusM;  // the arc c over sin(c), in metres
  return {north * scale, east * scale};
}

GeoPoint MapProjection::reproject(const NedPoint& p) const {
  const double x = p.north_m / kEarthRadiusM, y = p.east_m / kEarthRadiusM;
  const double c = std::hypot(x, y);
  if (c == 0.0) return reference_;
  const double sin_c_over_c = std::sin(c) / c, cos_c = std::cos(c);
  const double sin_lat = std::clamp(cos_c * sin_lat_ + x * sin_c_over_c * cos_lat_, -1.0, 1.0);
  const double d_lon = std::atan2(y * sin_c_over_c, cos_lat_ * cos_c - x * sin_lat_ * sin_c_over_c);
  GeoPoint out{std::asin(sin_lat) / kDegToRad, reference_.lon_deg + d_lon / kDegToRad};
  if (out.lon_deg > 180.0) out.lon_deg -= 360.0;
  if (out.lon_deg <= -180.0) out.lon_deg += 360.0;
  return out;
}

}  // namespace swa::px4
