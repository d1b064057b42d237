#pragma once
// ArduPilot's DDS messages (sensor_msgs/Imu, ardupilot_msgs/Status, geometry_msgs/TwistStamped as its cmd_vel) <->
// the autopilot library's types (swa/autopilot/ardupilot.h has the conventions). For the bridge and the simulator's
// ArduPilot stand-in.

#include <cstdint>
#include <optional>

#include <swa/ros/ArdupilotStatus.h>
#include <swa/ros/Imu.h>
#include <swa/ros/NavSatFix.h>
#include <swa/ros/TFMessage.h>
#include <swa/ros/TwistStamped.h>

#include "swa/autopilot/ardupilot.h"
#include "swa/autopilot/bridge_core.h"
#include "swa/autopilot/navsat.h"
#include "swa/autopilot/odometry_feed.h"
#include "swa/autopilot/quaternion_order.h"

namespace swa::wire {

std::optional<std::uint64_t> timestampUsOf(const builtin_interfaces::msg::Time& t);

// The attitude in an IMU message, read in `layout`; its orientation fields as they came and its linear acceleration
// (for --ap-quaternion auto). And an IMU message of an attitude, its fields in `layout`, with the specific force
// `force_frd` (FRD body, m/s^2), or without it that of a vehicle at rest, and no angular velocity (its covariance says
// "no estimate").
px4::Quaternion attitudeOf(const sensor_msgs::msg::Imu& m, ardupilot::QuaternionLayout layout);
ardupilot::OrientationFields orientationFieldsOf(const sensor_msgs::msg::Imu& m);
ardupilot::SpecificForce specificForceOf(const sensor_msgs::msg::Imu& m);
sensor_msgs::msg::Imu imuMessage(std::uint64_t timestamp_us, const px4::Quaternion& q,
                                 ardupilot::QuaternionLayout layout = ardupilot::QuaternionLayout::kRos,
                                 const std::optional<ardupilot::SpecificForce>& force_frd = std::nullopt);

ardupilot_msgs::msg::Status statusMessage(std::uint64_t timestamp_us, bool armed, std::uint8_t mode, bool failsafe_ekf);

// ArduPilot's GNSS fix: what the bridge needs of it (a time it cannot read is 0, older than any), and a fix of a
// position (a valid one; the stand-in sends nothing while its GNSS is lost, as ArduPilot does).
ardupilot::NavSatReport navSatReportOf(const sensor_msgs::msg::NavSatFix& m);
sensor_msgs::msg::NavSatFix navSatFix(std::uint64_t timestamp_us, double lat_deg, double lon_deg, double std_m);

// The core's setpoint as cmd_vel: frame "map", stamped with the answered sample's time; and what a cmd_vel commands.
geometry_msgs::msg::TwistStamped cmdVel(const autopilot::Setpoint& s);
struct CmdVel {
  bool map_frame = false;  // ArduPilot ignores any other frame id but base_link (body FLU), which SWA never sends
  std::optional<std::uint64_t> timestamp_us;
  ardupilot::EnuTwist twist;
};
CmdVel cmdVelOf(const geometry_msgs::msg::TwistStamped& m);

// The agent's estimate as ArduPilot's external odometry (rt/ap/tf, issue #43): one "odom" -> "base_link" transform,
// the only pair AP_DDS_External_Odom.cpp takes. It turns the translation (x, y, z) into NED as (x, -y, -z) and the
// rotation (w, x, y, z) as (w, x, -y, -z), so odom's axes are north, west, up: SWA's east and north go in as (north,
// -east), up is 0 (the pre-flight table keeps height on the barometer), and the rotation is the vehicle's own attitude
// turned back. No velocity: AP_DDS has no path for one. Stamped 0: ArduPilot reads the stamp as its own boot time in
// milliseconds with no offset, fuses a stamp not after its time as current (less VISO_DELAY_MS) and never one after
// it, such as a UTC stamp; so the estimate's age goes in VISO_DELAY_MS.
tf2_msgs::msg::TFMessage externalOdometry(const autopilot::Odometry& o, const px4::Quaternion& attitude);
// What ArduPilot takes of a TFMessage: the odom -> base_link transform's stamp [ns] and its north, east position; none
// when there is no such transform.
struct ExternalOdomReport {
  agent::StampNs stamp_ns = 0;
  double north_m = 0.0, east_m = 0.0;
};
std::optional<ExternalOdomReport> externalOdomOf(const tf2_msgs::msg::TFMessage& m);

}  // namespace swa::wire
