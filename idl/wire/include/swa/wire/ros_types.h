#pragma once
// SWA messages as the standard ROS 2 types that mean the same thing, for ROS tools that know no SWA package
// (SWA_NAMING=ros2). REP-103: the velocity setpoint's frame is ENU-aligned (x east, y north, z up) at the UAV, named
// swa/uav<I>/enu; the command is horizontal, so linear.z, angular.x and angular.y are 0, and angular.z is the yaw
// rate: about z up, counter-clockwise seen from above, SWA's own sense, so no sign changes.

#include <cstdint>
#include <string>

#include <swa/msg/VelocitySetpoint.h>
#include <swa/ros/TwistStamped.h>

namespace swa::wire {

// The frame_id of UAV `uav_id`'s velocity setpoints.
std::string enuFrameId(std::uint32_t uav_id);

// builtin_interfaces/Time of a stamp in nanoseconds (floor: nanosec stays in [0, 1e9) for negative stamps too).
builtin_interfaces::msg::Time rosTime(std::int64_t stamp_ns);

// The setpoint as geometry_msgs/TwistStamped: header.stamp = the setpoint's stamp, frame swa/uav<I>/enu.
geometry_msgs::msg::TwistStamped toTwistStamped(const msg::VelocitySetpoint& m);

}  // namespace swa::wire
