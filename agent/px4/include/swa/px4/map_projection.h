#pragma once
// PX4's map projection (its lib/geo MapProjection, which EKF2 uses for its global origin): the azimuthal equidistant
// projection on a sphere of 6371 km around a reference point. PX4's local x (north) and y (east) are this projection
// around vehicle_local_position's ref_lat, ref_lon, so undoing a change of that reference (issue #46) takes the same
// projection, not the WGS-84 local tangent of swa/autopilot/navsat.h: at mid latitudes the sphere's east-west radius is
// 0.3 % shorter than the ellipsoid's, 1.5 m over a 500 m shift east. (swa_autopilot builds on this library, so this
// library could not use that one anyway.)
//
// Double throughout, in forms without the cancellation of PX4's acos near the reference (PX4 only needs float32
// metres): a round trip is exact to nanometres over kilometres.

namespace swa::px4 {

struct GeoPoint {
  double lat_deg = 0.0, lon_deg = 0.0;
};

// A horizontal position in PX4's local frame [m]: x north, y east (NED).
struct NedPoint {
  double north_m = 0.0, east_m = 0.0;
};

// Whether a reference point is one PX4 could project around: finite, |lat| < 90 (at a pole north is undefined),
// |lon| <= 180.
bool isProjectionReference(const GeoPoint& p);

class MapProjection {
 public:
  // `reference` must pass isProjectionReference.
  explicit MapProjection(const GeoPoint& reference);

  const GeoPoint& reference() const { return reference_; }
  // A point on the ground in this frame (PX4's project) and back (PX4's reproject).
  NedPoint project(const GeoPoint& p) const;
  GeoPoint reproject(const NedPoint& p) const;

 private:
  GeoPoint reference_;
  double sin_lat_ = 0.0, cos_lat_ = 1.0;
};

}  // namespace swa::px4
