#pragma once
// PX4's messages <-> the PX4 library's types (swa/px4/): the bridge's and the simulator's PX4 stand-in's one place for
// message fields. Which release has which layout: swa/px4/release.h (VehicleStatus and VehicleLocalPosition changed in
// v1.16, SensorGps in v1.17; the rest SWA uses has v1.15's layout throughout). Frames are converted in
// swa/px4/frames.h, not here: these only move values (float32 on PX4's side).

#include <cstdint>
#include <optional>

#include <swa/msg/BridgeState.h>
#include <swa/px4/OffboardControlMode_v1_15.h>
#include <swa/px4/SensorCombined_v1_15.h>
#include <swa/px4/TrajectorySetpoint_v1_15.h>
#include <swa/px4/VehicleAttitude_v1_15.h>
#include <swa/px4/VehicleCommandAck_v1_15.h>
#include <swa/px4/VehicleCommand_v1_15.h>
#include <swa/px4/VehicleOdometry_v1_15.h>
#include <swa/px4/VehicleStatus_v1_15.h>
#include <swa/px4/VehicleStatus_v1_16.h>

#include "swa/autopilot/bridge_core.h"
#include "swa/autopilot/odometry_feed.h"
#include "swa/px4/frames.h"
#include "swa/px4/gnss.h"
#include "swa/px4/map_projection.h"

namespace swa::wire {

px4::Quaternion quaternionOf(const px4_msgs::msg::VehicleAttitude& m);
px4_msgs::msg::VehicleAttitude vehicleAttitude(std::uint64_t timestamp_us, const px4::Quaternion& q);
// The accelerometer part of sensor_combined, sampled at `timestamp_us` (relative time 0), FRD body, m/s^2; the gyro
// left at 0 (SWA reads none), the integration periods those of a 100 Hz IMU.
px4_msgs::msg::SensorCombined sensorCombined(std::uint64_t timestamp_us, const agent::Vec3& specific_force_frd);

// A velocity-only setpoint: position, acceleration, jerk and yaw NaN (not controlled), as PX4's offboard velocity
// control wants them; yawspeed the setpoint's (yaw NaN: PX4 follows the rate, 0 holds the heading).
px4_msgs::msg::TrajectorySetpoint trajectorySetpoint(const autopilot::Setpoint& s);
// The setpoint's NED velocity and yawspeed, and whether it is velocity-only (position NaN, velocity finite).
px4::NedVelocity velocityOf(const px4_msgs::msg::TrajectorySetpoint& m);
double yawspeedOf(const px4_msgs::msg::TrajectorySetpoint& m);
bool isVelocityOnly(const px4_msgs::msg::TrajectorySetpoint& m);

// The offboard heartbeat for velocity control: velocity true, every other level false.
px4_msgs::msg::OffboardControlMode velocityControlMode(std::uint64_t timestamp_us);
bool isVelocityControl(const px4_msgs::msg::OffboardControlMode& m);

// Arm, or switch to offboard (DO_SET_MODE, custom main mode OFFBOARD), for the vehicle `target_system` (0: whichever
// vehicle reads this namespace), from an external component. Stamped 0: PX4 stamps it on receipt.
px4_msgs::msg::VehicleCommand vehicleCommand(autopilot::VehicleRequest request, std::uint8_t target_system);

// vehicle_status as the simulator's stand-in sends it, in the layout of v1.15 (px4_msgs::msg::VehicleStatus) or
// v1.16+ (px4_v1_16::px4_msgs::msg::VehicleStatus): what SWA reads and what a healthy multirotor's PX4 fills in.
template <class Status>
Status vehicleStatus(std::uint64_t timestamp_us, std::uint8_t arming_state, std::uint8_t nav_state, bool failsafe,
                     std::uint8_t system_id) {
  Status m;
  m.timestamp(timestamp_us);
  m.arming_state(arming_state);
  m.nav_state(nav_state);
  m.nav_state_user_intention(nav_state);
  m.nav_state_timestamp(timestamp_us);
  m.failsafe(failsafe);
  m.vehicle_type(1);  // rotary wing
  m.system_id(system_id);
  m.component_id(1);
  m.pre_flight_checks_pass(true);
  return m;
}

// GNSS as the simulator's stand-in reports it (vehicle.gnss_source = autopilot), in any release's layout of SensorGps
// and VehicleLocalPosition: a 3D fix with 10 satellites and a valid horizontal position while the scenario's GNSS is
// valid, no fix and xy_valid false while it is lost. The local frame is NED with the world's origin.
template <class Gps>
Gps sensorGps(std::uint64_t timestamp_us, const agent::GnssSample& g) {
  Gps m;
  m.timestamp(timestamp_us);
  m.timestamp_sample(timestamp_us);
  m.fix_type(g.valid ? 3 : 0);
  m.satellites_used(g.valid ? 10 : 0);
  m.eph(static_cast<float>(g.std_m));
  m.epv(static_cast<float>(2.0 * g.std_m));
  return m;
}

// The global reference of vehicle_local_position's x, y (xy_global, ref_timestamp, ref_lat, ref_lon).
struct LocalReference {
  std::uint64_t timestamp_us = 0;  // when PX4 set it, on its clock
  px4::GeoPoint point;
};

// The estimator's own word (`xy_valid`, which is also v_xy_valid, and `dead_reckoning`) when the stand-in models EKF2
// (px4_estimator.h); without it, xy_valid is the fix's. With a `reference`, xy_global and the ref_ fields say which
// origin g's position is relative to (the altitude has none: z_global false); without one, xy_global is false.
template <class Position>
Position vehicleLocalPosition(std::uint64_t timestamp_us, const agent::GnssSample& g,
                              std::optional<bool> xy_valid = std::nullopt, bool dead_reckoning = false,
                              const std::optional<LocalReference>& reference = std::nullopt) {
  Position m;
  m.timestamp(timestamp_us);
  m.timestamp_sample(timestamp_us);
  m.xy_valid(xy_valid.value_or(g.valid));
  m.v_xy_valid(xy_valid.value_or(g.valid));
  m.dead_reckoning(dead_reckoning);
  m.x(static_cast<float>(g.position_m.y()));  // north
  m.y(static_cast<float>(g.position_m.x()));  // east
  m.eph(static_cast<float>(g.std_m));
  if (reference) {
    m.xy_global(true);
    m.ref_timestamp(reference->timestamp_us);
    m.ref_lat(reference->point.lat_deg);
    m.ref_lon(reference->point.lon_deg);
  }
  return m;
}

template <class Gps>
px4::GpsReport gpsReportOf(const Gps& m) {
  return {m.timestamp(), m.fix_type()};
}

// The same fields in v1.15's layout (px4_msgs::msg::VehicleLocalPosition) and v1.16's (px4_v1_16::...).
template <class Position>
px4::LocalPositionReport localPositionOf(const Position& m) {
  return {m.timestamp(), m.xy_valid(),  m.dead_reckoning(), m.x(),       m.y(),
          m.eph(),       m.xy_global(), m.ref_timestamp(),  m.ref_lat(), m.ref_lon()};
}

// The agent's estimate as external vision (fmu/in/vehicle_visual_odometry, issue #43), stamped on the vehicle's
// clock like the setpoints: position and velocity in NED (SWA's east and north as PX4's y and x). Down is not SWA's:
// 0 with a variance no filter trusts (1e4), since EKF2 takes a position only with all three components finite and the
// pre-flight table leaves EKF2_EV_CTRL's vertical bit off. q NaN: the attitude is the vehicle's own. No reset of the
// agent is hidden: reset_counter is the feed's.
px4_msgs::msg::VehicleOdometry vehicleOdometry(const autopilot::Odometry& o);
// What EKF2 could fuse of a sample (EKF2.cpp UpdateExtVisionSample): a position with all three components finite in
// frame NED or FRD, a velocity likewise in NED, FRD or body FRD.
struct VisionReport {
  bool position = false;
  bool velocity = false;
};
VisionReport visionReportOf(const px4_msgs::msg::VehicleOdometry& m);

msg::BridgeState bridgeState(const autopilot::BridgeCore& core, std::uint32_t uav_id, std::uint32_t seq,
                             std::uint64_t commands_refused, const std::string& last_event);

}  // namespace swa::wire
