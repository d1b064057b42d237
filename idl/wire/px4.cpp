#include "swa/wire/px4.h"

#include <array>
#include <cmath>
#include <limits>

#include "swa/px4/vehicle.h"

namespace swa::wire {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

msg::BridgeLink linkOf(autopilot::Link link) {
  switch (link) {
    case autopilot::Link::kNoAttitude:
      return msg::LINK_NO_ATTITUDE;
    case autopilot::Link::kNoAgent:
      return msg::LINK_NO_AGENT;
    case autopilot::Link::kFresh:
      return msg::LINK_FRESH;
    case autopilot::Link::kStale:
      return msg::LINK_STALE;
    case autopilot::Link::kAgentLost:
      return msg::LINK_AGENT_LOST;
    case autopilot::Link::kAttitudeLost:
      return msg::LINK_ATTITUDE_LOST;
  }
  return msg::LINK_NO_ATTITUDE;
}

}  // namespace

px4::Quaternion quaternionOf(const px4_msgs::msg::VehicleAttitude& m) {
  return {m.q()[0], m.q()[1], m.q()[2], m.q()[3]};
}

px4_msgs::msg::VehicleAttitude vehicleAttitude(std::uint64_t timestamp_us, const px4::Quaternion& q) {
  px4_msgs::msg::VehicleAttitude m;
  m.timestamp(timestamp_us);
  m.timestamp_sample(timestamp_us);
  m.q({static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z)});
  m.delta_q_reset({0.0f, 0.0f, 0.0f, 0.0f});
  return m;
}

px4_msgs::msg::SensorCombined sensorCombined(std::uint64_t timestamp_us, const agent::Vec3& specific_force_frd) {
  px4_msgs::msg::SensorCombined m;
  m.timestamp(timestamp_us);
  m.gyro_integral_dt(10'000);
  m.accelerometer_timestamp_relative(0);
  m.accelerometer_m_s2({static_cast<float>(specific_force_frd.x()), static_cast<float>(specific_force_frd.y()),
                        static_cast<float>(specific_force_frd.z())});
  m.accelerometer_integral_dt(10'000);
  return m;
}

px4_msgs::msg::TrajectorySetpoint trajectorySetpoint(const autopilot::Setpoint& s) {
  px4_msgs::msg::TrajectorySetpoint m;
  m.timestamp(s.timestamp_us);
  m.position({kNaN, kNaN, kNaN});
  m.velocity(
      {static_cast<float>(s.velocity.north), static_cast<float>(s.velocity.east), static_cast<float>(s.velocity.down)});
  m.acceleration({kNaN, kNaN, kNaN});
  m.jerk({kNaN, kNaN, kNaN});
  m.yaw(kNaN);
  m.yawspeed(static_cast<float>(s.yawspeed_radps));
  return m;
}

px4::NedVelocity velocityOf(const px4_msgs::msg::TrajectorySetpoint& m) {
  return {m.velocity()[0], m.velocity()[1], m.velocity()[2]};
}

double yawspeedOf(const px4_msgs::msg::TrajectorySetpoint& m) { return m.yawspeed(); }

bool isVelocityOnly(const px4_msgs::msg::TrajectorySetpoint& m) {
  for (const float p : m.position()) {
    if (!std::isnan(p)) return false;
  }
  return std::isfinite(m.velocity()[0]) && std::isfinite(m.velocity()[1]);
}

px4_msgs::msg::OffboardControlMode velocityControlMode(std::uint64_t timestamp_us) {
  px4_msgs::msg::OffboardControlMode m;
  m.timestamp(timestamp_us);
  m.velocity(true);
  return m;
}

bool isVelocityControl(const px4_msgs::msg::OffboardControlMode& m) {
  // The first true level from the top is the one PX4 controls.
  return !m.position() && m.velocity();
}

px4_msgs::msg::VehicleCommand vehicleCommand(autopilot::VehicleRequest request, std::uint8_t target_system) {
  px4_msgs::msg::VehicleCommand m;
  m.timestamp(0);
  if (request == autopilot::VehicleRequest::kArm) {
    m.command(px4::kCmdComponentArmDisarm);
    m.param1(1.0f);
  } else {
    m.command(px4::kCmdDoSetMode);
    m.param1(px4::kModeFlagCustomModeEnabled);
    m.param2(px4::kCustomMainModeOffboard);
  }
  m.target_system(target_system);
  m.target_component(1);
  m.source_system(1);
  m.source_component(1);
  m.from_external(true);
  return m;
}

msg::BridgeState bridgeState(const autopilot::BridgeCore& core, std::uint32_t uav_id, std::uint32_t seq,
                             std::uint64_t commands_refused, const std::string& last_event) {
  const autopilot::BridgeCounters& c = core.counters();
  msg::BridgeState m;
  m.header().seq(seq);
  if (const auto t = core.newestTimestampUs()) m.header().stamp_ns(px4::stampNsOf(*t).value_or(0));
  m.uav_id(uav_id);
  m.link(linkOf(core.link()));
  m.armed(core.armed());
  m.nav_state(core.mode().value_or(255));
  m.attitude_in(c.attitude_in);
  m.attitude_rejected(c.attitude_rejected + c.attitude_out_of_order);
  m.commands_applied(c.commands_applied);
  m.commands_ignored(c.commands_replayed + c.commands_not_newer + c.commands_unknown_sample + c.commands_nonfinite +
                     commands_refused);
  m.setpoints_out(c.setpoints_out);
  m.heartbeats_out(c.heartbeats_out);
  m.requests_out(c.requests_out);
  m.last_event(last_event);
  return m;
}

px4_msgs::msg::VehicleOdometry vehicleOdometry(const autopilot::Odometry& o) {
  constexpr std::uint8_t kNed = 1;          // POSE_FRAME_NED, VELOCITY_FRAME_NED
  constexpr float kUnknownVariance = 1e4f;  // [m^2], [m^2/s^2]: down is not SWA's
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::uint64_t t = px4::timestampUsOf(o.stamp_ns).value_or(0);
  px4_msgs::msg::VehicleOdometry m;
  m.timestamp(t);
  m.timestamp_sample(t);
  m.pose_frame(kNed);
  m.position({static_cast<float>(o.position_m.y()), static_cast<float>(o.position_m.x()), 0.0f});
  m.q({nan, nan, nan, nan});
  m.velocity_frame(kNed);
  m.velocity({static_cast<float>(o.velocity_mps.y()), static_cast<float>(o.velocity_mps.x()), 0.0f});
  m.angular_velocity({nan, nan, nan});
  m.position_variance(
      {static_cast<float>(o.position_var_m2.y()), static_cast<float>(o.position_var_m2.x()), kUnknownVariance});
  m.orientation_variance({nan, nan, nan});
  m.velocity_variance(
      {static_cast<float>(o.velocity_var_m2ps2.y()), static_cast<float>(o.velocity_var_m2ps2.x()), kUnknownVariance});
  m.reset_counter(o.reset_counter);
  m.quality(0);
  return m;
}

VisionReport visionReportOf(const px4_msgs::msg::VehicleOdometry& m) {
  const auto finite = [](const std::array<float, 3>& v) {
    return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
  };
  const std::uint8_t pose = m.pose_frame(), velocity = m.velocity_frame();
  return {finite(m.position()) && (pose == 1 || pose == 2),
          finite(m.velocity()) && (velocity == 1 || velocity == 2 || velocity == 3)};
}

}  // namespace swa::wire
