#pragma once
// One PX4 autopilot (v1.15 to v1.17 alike) as its offboard interface behaves, for swa_sim with vehicle.interface = px4
// (the node publishes its vehicle_attitude and vehicle_status, and feeds it what arrives on /fmu/in). Pure: no DDS,
// time is the simulation time a message arrived at.
//
// What is modelled (PX4's offboard rules, ROS2-PX4-NOTES.md):
//   - it starts armed, hovering in Hold (nav_state AUTO_LOITER): the scenario starts airborne, before the swarm's
//     offboard control is switched on;
//   - the offboard signal is fresh while an offboard_control_mode arrived within COM_OF_LOSS_T;
//   - VEHICLE_CMD_DO_SET_MODE to the custom main mode OFFBOARD is accepted only while the signal is fresh (else
//     temporarily rejected); arming is accepted; other commands are unsupported;
//   - in OFFBOARD it flies the newest trajectory_setpoint's horizontal velocity while the signal is fresh, the control
//     mode is velocity and the setpoint is velocity-only (position NaN); a setpoint with a position, or a control mode
//     other than velocity, is not simulated: the vehicle holds and says so once;
//   - the signal lost in OFFBOARD is PX4's offboard-loss failsafe: Hold (nav_state AUTO_LOITER, failsafe set), until
//     offboard is requested again (the vehicle does not return to OFFBOARD by itself).
// "Hold" here is zero velocity command, the simulator's own hover (PX4's COM_OBL_RC_ACT default, Position mode, also
// holds position when the sticks are centred).
// With the EKF modelled (px4_estimator.h, issue #43), its horizontal validity decides too, as commander does
// (HealthAndArmingChecks/checks/offboardCheck.cpp, failsafe/failsafe.cpp checkModeFallback):
//   - offboard with velocity setpoints needs a valid local velocity: DO_SET_MODE to OFFBOARD is temporarily rejected
//     while v_xy_valid is false;
//   - in OFFBOARD, v_xy_valid turning false is an offboard loss at once: the fallback COM_OBL_RC_ACT = Position cannot
//     run without a position, so the vehicle is in Altitude mode (nav_state ALTCTL, failsafe set): no horizontal
//     control, here a zero velocity command like Hold, but out of SWA's control until offboard is requested again;
//   - in the offboard-loss failsafe's Hold, the position turning invalid (nothing aids EKF2 any more: GNSS gone and no
//     external vision, e.g. SWA's agent killed) leaves a mode that cannot run: checkModeFallback's RTL needs a global
//     position and Land a local one, so the vehicle descends (nav_state DESCEND, a second "control lost" event). The
//     Hold the vehicle starts in, before the swarm engages it, is left alone: the scenario has no take-off.
// Without it (no EKF given) the estimate is always valid, as before issue #43.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "swa/agent/samples.h"
#include "swa/px4/frames.h"
#include "swa/sim/px4_estimator.h"
#include "swa/sim/standin_event.h"

namespace swa::sim {

class Px4Standin {
 public:
  // `offboard_loss_timeout_s`: PX4's COM_OF_LOSS_T; `ekf`: EKF2's parameters, none to leave its estimate always valid.
  explicit Px4Standin(double offboard_loss_timeout_s, const std::optional<Px4EstimatorParams>& ekf = std::nullopt);

  // The vehicle's GNSS at `now` (every step), and a vehicle_visual_odometry sample (usable position / velocity).
  void gnss(agent::StampNs now, bool fix);
  void visualOdometry(agent::StampNs now, bool position, bool velocity);

  void offboardControlMode(agent::StampNs now, bool velocity_control);
  void trajectorySetpoint(const px4::NedVelocity& velocity, bool velocity_only);
  // A VehicleCommand: its VehicleCommandAck result (0 accepted, 1 temporarily rejected, 3 unsupported).
  std::uint8_t vehicleCommand(agent::StampNs now, std::uint32_t command, float param1, float param2);

  struct Decision {
    agent::Vec2 velocity_mps = agent::Vec2::Zero();  // stable frame (x east, y north)
    bool following = false;                          // flying the offboard setpoint (false: holding)
  };
  // What the vehicle flies at `now`, and what changed (offboard lost, engaged, an unsimulated setpoint) since the
  // last call, for the scenario's events.
  Decision step(agent::StampNs now);
  std::vector<StandinEvent> takeEvents();

  std::uint8_t armingState() const { return arming_state_; }
  std::uint8_t navState() const { return nav_state_; }
  bool failsafe() const { return failsafe_; }
  // vehicle_local_position's xy_valid and v_xy_valid (one flag in EKF2), and dead_reckoning.
  bool localPositionValid() const { return !ekf_ || ekf_->xyValid(); }
  bool modelsEstimator() const { return ekf_.has_value(); }
  bool deadReckoning() const { return ekf_ && ekf_->deadReckoning(); }
  // How long the offboard signal had been silent when it was last lost [s] (the value of the failsafe event).
  double lostAfterS() const { return lost_after_s_; }
  // The value of this step's events: lostAfterS() while in failsafe, else 0 (as ArduPilot's stand-in).
  double eventValue() const { return failsafe_ ? lost_after_s_ : 0.0; }

 private:
  bool signalFresh(agent::StampNs now) const;
  // How long EKF2 has been dead-reckoning at `now` [s] (0 while aided): the value of the estimator's failsafe events.
  double deadReckoningS(agent::StampNs now) const;
  void lose(std::uint8_t nav_state, const char* text);

  agent::StampNs loss_timeout_ns_;
  std::uint8_t arming_state_;
  std::uint8_t nav_state_;
  bool failsafe_ = false;
  std::optional<agent::StampNs> last_heartbeat_ns_;
  bool velocity_control_ = false;
  std::optional<px4::NedVelocity> setpoint_;
  bool setpoint_velocity_only_ = true;
  bool unsimulated_reported_ = false;
  double lost_after_s_ = 0.0;
  std::optional<Px4Estimator> ekf_;
  std::optional<agent::StampNs> dead_reckoning_since_ns_;  // for the failsafe event's value
  std::vector<StandinEvent> events_;
};

}  // namespace swa::sim
