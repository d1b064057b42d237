#include "swa/wire/ros_types.h"

namespace swa::wire {

std::string enuFrameId(std::uint32_t uav_id) { return "swa/uav" + std::to_string(uav_id) + "/enu"; }

builtin_interfaces::msg::Time rosTime(std::int64_t stamp_ns) {
  constexpr std::int64_t kNsPerS = 1'000'000'000;
  std::int64_t sec = stamp_ns / kNsPerS;
  std::int64_t nanosec = stamp_ns % kNsPerS;
  if (nanosec < 0) {
    nanosec += kNsPerS;
    --sec;
  }
  builtin_interfaces::msg::Time t;
  t.sec(static_cast<std::int32_t>(sec));
  t.nanosec(static_cast<std::uint32_t>(nanosec));
  return t;
}

geometry_msgs::msg::TwistStamped toTwistStamped(const msg::VelocitySetpoint& m) {
  geometry_msgs::msg::TwistStamped out;
  out.header().stamp(rosTime(m.header().stamp_ns()));
  out.header().frame_id(enuFrameId(m.uav_id()));
  out.twist().linear().x(m.vx_mps());
  out.twist().linear().y(m.vy_mps());
  out.twist().angular().z(m.yaw_rate_radps());
  return out;
}

}  // namespace swa::wire
