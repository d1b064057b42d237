#pragma once
// GNSS and its loss from ArduPilot (issue #27): AP_DDS's rt/<ns>/navsat (sensor_msgs/NavSatFix) turned into SWA's
// GNSS samples. Pure: no DDS; the bridge feeds it the messages' fields and the vehicle's time.
//
// What ArduPilot sends (AP_DDS_Client.cpp, update_topic(NavSatFix)): a message when its GPS has a new fix, with
// status.status >= 0 for a 2D/3D fix or better and -1 for none; nothing at all while the receiver is unhealthy, and
// nothing new while it has no new fix. So the loss comes either as a status of -1 (at once) or as silence: no
// NavSatFix for `silence_s` of vehicle time (the IMU's stamps) is a loss too. A fix is valid with status >= 0 and a
// finite latitude and longitude.
//
// The position is the fix's latitude and longitude in a local east-north frame whose origin is the first valid fix
// (WGS 84, the local radii of curvature at that origin: exact to centimetres over kilometres). The agent needs only
// differences of its own fixes. std_m: the root of the mean horizontal variance when ArduPilot says it knows the
// covariance, else `unknown_std_m`.

#include <cstdint>
#include <optional>

#include "swa/agent/samples.h"

namespace swa::ardupilot {

struct NavSatReport {
  std::uint64_t timestamp_us = 0;
  std::int8_t status = -1;  // sensor_msgs/NavSatStatus: -1 no fix, 0 fix, 1 SBAS, 2 GBAS
  double latitude_deg = 0.0, longitude_deg = 0.0;
  std::uint8_t covariance_type = 0;                        // 0 unknown
  double variance_east_m2 = 0.0, variance_north_m2 = 0.0;  // position_covariance[0], [4] (ENU)
};

struct NavSatForwardConfig {
  double silence_s = 0.5;      // ArduPilot's GPS reports at 5-10 Hz: half a second without one is a lost receiver
  double unknown_std_m = 2.5;  // a fix without a known covariance
};

// A local east-north frame on WGS 84 around an origin [deg].
struct LocalTangent {
  double origin_lat_deg = 0.0, origin_lon_deg = 0.0;
  agent::Vec2 enuOf(double lat_deg, double lon_deg) const;  // [m]
  void latLonOf(const agent::Vec2& enu_m, double& lat_deg, double& lon_deg) const;
};

class NavSatForward {
 public:
  explicit NavSatForward(const NavSatForwardConfig& config = {}) : config_(config) {}

  // A NavSatFix: the GNSS sample for the agent (valid or not), or nullopt if it is older than the last one.
  std::optional<agent::GnssSample> onNavSat(const NavSatReport& r);
  // The vehicle's time (every attitude sample): a loss (a valid=false sample) once, when the last sample said valid
  // and no NavSatFix came for silence_s: at the first attitude sample at least silence_s after the last fix.
  std::optional<agent::GnssSample> onVehicleTime(std::uint64_t now_us);

 private:
  NavSatForwardConfig config_;
  std::optional<LocalTangent> origin_;
  std::optional<std::uint64_t> last_us_;
  bool valid_ = false;
};

}  // namespace swa::ardupilot
