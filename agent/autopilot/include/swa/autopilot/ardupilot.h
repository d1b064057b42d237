#pragma once
// What SWA uses of ArduPilot's DDS interface (AP_DDS, Copter 4.5+; libraries/AP_DDS in ArduPilot's source), without
// DDS: the modes, the stamps, the frames of its IMU message and of cmd_vel. The one place where ArduPilot's
// conventions meet SWA's; the bridge's adapter and the simulator's stand-in both use it.
//
//   IMU   rt/<ns>/imu/experimental/data, sensor_msgs/Imu, frame "base_link_ned": orientation is the AHRS quaternion
//         FRD body -> NED earth, the same attitude PX4 sends (swa/px4/frames.h converts it). AP_DDS releases of 2024
//         (and perhaps later: not confirmed) write its (w, x, y, z) into the message's (x, y, z, w) fields, a fork
//         fixes it: QuaternionLayout::kWxyzInXyzw reads the former. Read in the wrong order, a level vehicle with
//         true heading psi (from north) reads as tilted: by pi - psi (heading north) when ArduPilot writes w, x, y,
//         z; by psi when it writes the ROS order. quaternion_order.h decides the order from gravity.
//         linear_acceleration is the specific force in FRD body axes. Stamps: builtin_interfaces/Time of the vehicle
//         (UTC when its clock is set, else time since boot), in whole microseconds.
//   cmd   rt/<ns>/cmd_vel, geometry_msgs/TwistStamped in frame "map": linear = ENU velocity (x east, y north, z up),
//         angular.z = yaw rate counter-clockwise from above (ArduPilot negates it for NED). SWA's stable frame is
//         x east, y north and its yaw rate counter-clockwise: the same numbers. Any other frame id is ignored by
//         ArduPilot; velocity commands count only in GUIDED and armed.

#include <cstdint>
#include <optional>
#include <string>

#include "swa/agent/samples.h"
#include "swa/px4/frames.h"

namespace swa::ardupilot {

// Copter's flight modes (ArduCopter/mode.h, MAVLink COPTER_MODE) that SWA names.
constexpr std::uint8_t kModeStabilize = 0;
constexpr std::uint8_t kModeAltHold = 2;
constexpr std::uint8_t kModeGuided = 4;  // the mode that takes cmd_vel
constexpr std::uint8_t kModeLoiter = 5;
constexpr std::uint8_t kModeRtl = 6;
constexpr std::uint8_t kModeLand = 9;
constexpr std::uint8_t kModeBrake = 17;
const char* copterModeName(std::uint8_t mode);

// ardupilot_msgs/Status's vehicle_type for Copter, and its failsafe codes.
constexpr std::uint8_t kVehicleTypeCopter = 2;
constexpr std::uint8_t kFailsafeEkf = 24;

// The frame ids ArduPilot's cmd_vel accepts; SWA sends "map" (ENU).
inline const char* const kMapFrame = "map";
inline const char* const kImuFrame = "base_link_ned";

enum class QuaternionLayout {
  kRos,         // x, y, z, w as sensor_msgs/Imu defines them
  kWxyzInXyzw,  // AP_DDS as of 2024: the message's x holds w, y holds x, z holds y, w holds z
};
std::optional<QuaternionLayout> parseQuaternionLayout(const std::string& text);  // "ros" | "wxyz"
// (the bridge's "auto" decides between them from the messages: quaternion_order.h)
const char* quaternionLayoutName(QuaternionLayout layout);

// The attitude (FRD -> NED) in an IMU message's orientation fields, read in `layout`.
px4::Quaternion attitudeOf(double x, double y, double z, double w, QuaternionLayout layout);
// And the fields to write for an attitude in `layout` (the stand-in writes the ROS order).
struct OrientationFields {
  double x = 0.0, y = 0.0, z = 0.0, w = 1.0;
};
OrientationFields orientationFieldsOf(const px4::Quaternion& q, QuaternionLayout layout = QuaternionLayout::kRos);

// builtin_interfaces/Time <-> the vehicle's microseconds. nullopt: a negative time, nanosec >= 1e9, or beyond
// uint64 microseconds. Sub-microsecond parts are dropped (ArduPilot stamps in whole microseconds).
std::optional<std::uint64_t> timestampUsOf(std::int32_t sec, std::uint32_t nanosec);
struct RosTime {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
};
std::optional<RosTime> rosTimeOf(std::uint64_t timestamp_us);  // nullopt beyond int32 seconds

// cmd_vel's twist for a NED velocity and a yawspeed about NED down (the bridge core's setpoint), and back.
struct EnuTwist {
  double east_mps = 0.0, north_mps = 0.0, up_mps = 0.0;
  double yaw_rate_radps = 0.0;  // counter-clockwise from above
};
EnuTwist enuTwistOf(const px4::NedVelocity& velocity, double yawspeed_radps);
agent::Vec2 stableVelocityOf(const EnuTwist& twist);

}  // namespace swa::ardupilot
