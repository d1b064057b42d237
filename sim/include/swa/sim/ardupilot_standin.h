#pragma once
// One ArduPilot Copter (4.5+, AP_DDS) as its external-control interface behaves, for swa_sim with vehicle.interface =
// ardupilot (the node publishes its IMU message and status, and feeds it what arrives on cmd_vel and its services).
// Pure: no DDS, time is the simulation time a message arrived at.
//
// What is modelled (AP_DDS_ExternalControl.cpp, AP_ExternalControl_Copter.cpp, ArduCopter/mode_guided.cpp):
//   - it starts armed, hovering in LOITER: the scenario starts airborne, before the swarm's control is switched on;
//   - arm_motors arms or disarms (always accepted); mode_switch to GUIDED, LOITER or BRAKE is accepted, to any other
//     mode refused (not simulated); the reply carries the mode after the request;
//   - cmd_vel counts only in frame "map" (ENU; "base_link" and others are not simulated: dropped, said once), only in
//     GUIDED and armed (otherwise dropped without an answer, as ArduPilot does); the vehicle then flies its horizontal
//     velocity and yaw rate;
//   - no cmd_vel for GUID_TIMEOUT in GUIDED: the vehicle stops and holds (zero velocity and yaw rate), still in GUIDED;
//     the next cmd_vel moves it again. ArduPilot has no offboard mode to fall out of.
// "Hold" is zero velocity command, the simulator's own hover.
// With the EKF modelled (ardupilot_estimator.h, issue #43), the vehicle's position decides too (ArduCopter/mode.cpp,
// ekf_check.cpp): GUIDED is refused while armed without a position ("requires position"), and in GUIDED the EKF
// failsafe (FS_EKF_ACTION default 1) lands the vehicle: LAND, no horizontal control (here a zero velocity command),
// cmd_vel ignored, out of SWA's control until GUIDED is requested again with a position. Without it (no EKF given)
// the position is always good, as before issue #43.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "swa/agent/samples.h"
#include "swa/autopilot/ardupilot.h"
#include "swa/sim/ardupilot_estimator.h"
#include "swa/sim/standin_event.h"

namespace swa::sim {

class ArdupilotStandin {
 public:
  // `guid_timeout_s`: ArduPilot's GUID_TIMEOUT; `ekf`: EKF3's setup, none to leave its position always good.
  explicit ArdupilotStandin(double guid_timeout_s, const std::optional<ArdupilotEstimatorParams>& ekf = std::nullopt);

  // The vehicle's GPS at `now` (every step), and an ap/tf odometry transform stamped `stamp_ns`: whether it was fused.
  void gnss(agent::StampNs now, bool fix);
  bool externalOdometry(agent::StampNs now, agent::StampNs stamp_ns);

  // A cmd_vel arriving at `now`.
  void cmdVel(agent::StampNs now, bool map_frame, const ardupilot::EnuTwist& twist);
  // The services: their replies (arm_motors: result; mode_switch: status and the mode after it).
  bool armMotors(bool arm);
  struct ModeReply {
    bool status = false;
    std::uint8_t curr_mode = 0;
  };
  ModeReply modeSwitch(std::uint8_t mode);

  struct Decision {
    agent::Vec2 velocity_mps = agent::Vec2::Zero();  // stable frame (x east, y north)
    double yaw_rate_radps = 0.0;                     // counter-clockwise
    bool following = false;                          // flying cmd_vel (false: holding)
  };
  // What the vehicle flies at `now`, and what changed since the last call (timed out, engaged, ...), for the
  // scenario's events.
  Decision step(agent::StampNs now);
  std::vector<StandinEvent> takeEvents();

  bool armed() const { return armed_; }
  bool positionOk() const { return !ekf_ || ekf_->positionOk(); }
  bool ekfFailsafe() const { return ekf_ && ekf_->ekfFailsafe(); }
  std::uint8_t mode() const { return mode_; }
  bool timedOut() const { return timed_out_; }
  // How long cmd_vel had been silent when the vehicle last stopped [s] (the value of the timeout event).
  double silentForS() const { return silent_for_s_; }
  // The value of this step's events: silentForS() while timed out, else 0 (as PX4's stand-in).
  double eventValue() const { return timed_out_ ? silent_for_s_ : 0.0; }

 private:
  agent::StampNs timeout_ns_;
  bool armed_ = true;
  std::uint8_t mode_ = ardupilot::kModeLoiter;
  std::optional<agent::StampNs> last_cmd_ns_;
  ardupilot::EnuTwist twist_;
  bool timed_out_ = false;
  bool other_frame_reported_ = false;
  double silent_for_s_ = 0.0;
  std::optional<ArdupilotEstimator> ekf_;
  std::vector<StandinEvent> events_;
};

}  // namespace swa::sim
