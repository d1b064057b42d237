#pragma once
// Every message SWA puts on the wire as JSON, field by field with the names of its .msg file (idl/swa_msgs/msg), as
// Fast DDS's generated code decodes it: what tests/ros2/decode_check.mjs compares an independent ROS 2 CDR decoder
// against. 64-bit integers are written as decimal strings (JSON numbers lose them above 2^53); doubles exactly.

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include <swa/msg/AgentState.h>
#include <swa/msg/Clock.h>
#include <swa/msg/Detections.h>
#include <swa/msg/GnssFix.h>
#include <swa/msg/Imu.h>
#include <swa/msg/ScenarioEvent.h>
#include <swa/msg/SwarmMetrics.h>
#include <swa/msg/SwarmTruth.h>
#include <swa/msg/VelocitySetpoint.h>
#include <swa/ros/TwistStamped.h>

namespace swa::testing::ros2 {

using nlohmann::json;

inline json big(std::int64_t v) { return std::to_string(v); }
inline json big(std::uint64_t v) { return std::to_string(v); }

inline json toJson(const msg::MessageHeader& h) { return {{"stamp_ns", big(h.stamp_ns())}, {"seq", h.seq()}}; }

inline json toJson(const msg::Imu& m) {
  return {{"header", toJson(m.header())},
          {"uav_id", m.uav_id()},
          {"roll_rad", m.roll_rad()},
          {"pitch_rad", m.pitch_rad()},
          {"heading_rad", m.heading_rad()},
          {"has_accelerometer", m.has_accelerometer()},
          {"accel_x_mps2", m.accel_x_mps2()},
          {"accel_y_mps2", m.accel_y_mps2()},
          {"accel_z_mps2", m.accel_z_mps2()},
          {"accel_roll_rad", m.accel_roll_rad()},
          {"accel_pitch_rad", m.accel_pitch_rad()}};
}

inline json toJson(const msg::Detections& m) {
  json items = json::array();
  for (const msg::Detection& d : m.items()) {
    items.push_back({{"target_id", d.target_id()},
                     {"x_m", d.x_m()},
                     {"y_m", d.y_m()},
                     {"has_covariance", d.has_covariance()},
                     {"cov_xx_m2", d.cov_xx_m2()},
                     {"cov_xy_m2", d.cov_xy_m2()},
                     {"cov_yy_m2", d.cov_yy_m2()}});
  }
  return {{"header", toJson(m.header())}, {"observer_id", m.observer_id()}, {"items", items}};
}

inline json toJson(const msg::GnssFix& m) {
  return {{"header", toJson(m.header())},
          {"uav_id", m.uav_id()},
          {"valid", m.valid()},
          {"x_m", m.x_m()},
          {"y_m", m.y_m()},
          {"std_m", m.std_m()}};
}

inline json toJson(const msg::VelocitySetpoint& m) {
  return {{"header", toJson(m.header())},
          {"uav_id", m.uav_id()},
          {"vx_mps", m.vx_mps()},
          {"vy_mps", m.vy_mps()},
          {"answered_stamp_ns", big(m.answered_stamp_ns())},
          {"answered_seq", m.answered_seq()},
          {"yaw_rate_radps", m.yaw_rate_radps()}};
}

inline json toJson(const msg::AgentState& m) {
  json ids = json::array();
  for (const std::int32_t id : m.neighbour_ids()) ids.push_back(id);
  return {{"header", toJson(m.header())},
          {"uav_id", m.uav_id()},
          {"mode", static_cast<std::uint32_t>(m.mode())},
          {"stage", static_cast<std::uint32_t>(m.stage())},
          {"est_x_m", m.est_x_m()},
          {"est_y_m", m.est_y_m()},
          {"est_vx_mps", m.est_vx_mps()},
          {"est_vy_mps", m.est_vy_mps()},
          {"pos_cov_xx_m2", m.pos_cov_xx_m2()},
          {"pos_cov_xy_m2", m.pos_cov_xy_m2()},
          {"pos_cov_yy_m2", m.pos_cov_yy_m2()},
          {"vel_cov_xx_m2ps2", m.vel_cov_xx_m2ps2()},
          {"vel_cov_xy_m2ps2", m.vel_cov_xy_m2ps2()},
          {"vel_cov_yy_m2ps2", m.vel_cov_yy_m2ps2()},
          {"frame_centre_x_m", m.frame_centre_x_m()},
          {"frame_centre_y_m", m.frame_centre_y_m()},
          {"frame_valid", m.frame_valid()},
          {"neighbour_ids", ids},
          {"confirmed_tracks", m.confirmed_tracks()},
          {"tentative_tracks", m.tentative_tracks()},
          {"rejected_nonfinite", big(m.rejected_nonfinite())},
          {"rejected_out_of_order", big(m.rejected_out_of_order())},
          {"rejected_oversize", big(m.rejected_oversize())},
          {"rejected_bad_id", big(m.rejected_bad_id())},
          {"rejected_implausible", big(m.rejected_implausible())},
          {"rejected_no_heading", big(m.rejected_no_heading())},
          {"rejected_future_stamp", big(m.rejected_future_stamp())},
          {"stamp_resyncs", big(m.stamp_resyncs())},
          {"commands_sent", big(m.commands_sent())},
          {"gnss_valid", m.gnss_valid()}};
}

inline json toJson(const msg::Clock& m) {
  return {{"header", toJson(m.header())},
          {"step", big(m.step())},
          {"sim_time_ns", big(m.sim_time_ns())},
          {"step_period_ns", big(m.step_period_ns())}};
}

inline json toJson(const msg::SwarmTruth& m) {
  json uavs = json::array();
  for (const msg::UavTruth& u : m.uavs()) {
    uavs.push_back({{"id", u.id()},
                    {"x_m", u.x_m()},
                    {"y_m", u.y_m()},
                    {"vx_mps", u.vx_mps()},
                    {"vy_mps", u.vy_mps()},
                    {"ax_mps2", u.ax_mps2()},
                    {"ay_mps2", u.ay_mps2()},
                    {"heading_rad", u.heading_rad()},
                    {"alive", u.alive()},
                    {"gnss_valid", u.gnss_valid()}});
  }
  return {{"header", toJson(m.header())}, {"uavs", uavs}};
}

inline json toJson(const msg::ScenarioEvent& m) {
  return {{"header", toJson(m.header())}, {"kind", static_cast<std::uint32_t>(m.kind())},
          {"uav_id", m.uav_id()},         {"other_uav_id", m.other_uav_id()},
          {"value", m.value()},           {"text", m.text()}};
}

inline json toJson(const msg::SwarmMetrics& m) {
  return {{"header", toJson(m.header())},
          {"mean_neighbor_distance_m", m.mean_neighbor_distance_m()},
          {"centroid_drift_mps", m.centroid_drift_mps()},
          {"min_separation_m", m.min_separation_m()},
          {"collisions", m.collisions()},
          {"spread_m", m.spread_m()},
          {"groups", m.groups()},
          {"formation_error_m", m.formation_error_m()},
          {"anees_position", m.anees_position()},
          {"anees_velocity", m.anees_velocity()},
          {"anees_band_low", m.anees_band_low()},
          {"anees_band_high", m.anees_band_high()},
          {"live_agents", m.live_agents()}};
}

inline json toJson(const geometry_msgs::msg::TwistStamped& m) {
  const auto vec = [](const geometry_msgs::msg::Vector3& v) { return json{{"x", v.x()}, {"y", v.y()}, {"z", v.z()}}; };
  return {{"header",
           {{"stamp", {{"sec", m.header().stamp().sec()}, {"nanosec", m.header().stamp().nanosec()}}},
            {"frame_id", m.header().frame_id()}}},
          {"twist", {{"linear", vec(m.twist().linear())}, {"angular", vec(m.twist().angular())}}}};
}

}  // namespace swa::testing::ros2
