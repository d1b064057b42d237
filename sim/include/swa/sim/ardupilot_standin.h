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

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "swa/agent/samples.h"
#include "swa/autopilot/ardupilot.h"

namespace swa::sim {

class ArdupilotStandin {
 public:
  // `guid_timeout_s`: ArduPilot's GUID_TIMEOUT.
  explicit ArdupilotStandin(double guid_timeout_s);

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
  std::vector<std::string> takeEvents();

  bool armed() const { return armed_; }
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
  std::vector<std::string> events_;
};

}  // namespace swa::sim
