#pragma once
// The autopilot bridge of one UAV without DDS, the rules PX4 and ArduPilot share (agent/bridge_node is the process
// around it, with one adapter per autopilot): the vehicle's attitude in, SWA's IMU sample out; SWA's velocity commands
// in, the vehicle's external-control stream out. Both autopilots are NED inside (attitude: the quaternion FRD body ->
// NED earth), so the core speaks NED and each adapter converts to its wire (PX4's trajectory_setpoint, ArduPilot's
// ENU cmd_vel). Time is an input: the vehicle's timestamps (its clock, in microseconds) for everything about commands,
// and a monotonic local clock `now_s` for the two things only it can tell (that the vehicle went quiet, and the
// heartbeat's period).
//
// The stream (PX4: offboard_control_mode "velocity" + trajectory_setpoint; ArduPilot: cmd_vel; deploy/README.md):
//   - every accepted command is sent at once, stamped with the vehicle timestamp of the attitude sample it answers, its
//     yaw rate as a yawspeed about NED down (PX4: yaw NaN, so that it follows the rate; 0 holds the heading);
//   - a command older than stale_after_s (vehicle time: newest attitude - the sample it answers) becomes zero
//     velocity and yawspeed 0, stamped like that command (it answers no new sample): the vehicle stops and hovers,
//     holding its heading, while the agent may still recover;
//   - no command for agent_lost_after_s, or no attitude from the vehicle for attitude_lost_after_s, stops the stream:
//     the autopilot's own failsafe takes over (PX4: offboard loss, COM_OF_LOSS_T and COM_OBL_RC_ACT; ArduPilot: the
//     GUIDED velocity timeout, GUID_TIMEOUT). The bridge never decides a failsafe itself;
//   - otherwise the heartbeat is repeated every heartbeat_period_s, stamped 0 (PX4 stamps it on receipt). ArduPilot has
//     no heartbeat, so its outbox has none, and while stale the zero setpoint itself is repeated at that period.
// Commands are accepted only if they answer a sample this bridge forwarded (not one from before it started: a
// restarted bridge is sent its writer's last command again) and are newer than the last one applied.
// It arms and requests the external-control mode (PX4: OFFBOARD; ArduPilot: GUIDED) only with `engage` (bench tests,
// the simulator), once the stream has run for engage_after_s of vehicle time, and again at most every engage_retry_s
// while the vehicle is not armed / not in that mode.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "swa/agent/samples.h"
#include "swa/autopilot/quaternion_order.h"
#include "swa/px4/frames.h"

namespace swa::autopilot {

using px4::NedVelocity;
using px4::Quaternion;

// What differs between the autopilots in the rules: names for people, and the mode that takes external commands.
struct Autopilot {
  const char* name = "PX4";
  std::uint8_t control_mode = 14;  // PX4: nav_state OFFBOARD; ArduPilot Copter: mode GUIDED (4)
  const char* control_mode_name = "offboard";
  const char* (*mode_name)(std::uint8_t mode) = nullptr;  // the mode's name in the logs
  bool heartbeat = true;  // PX4's offboard_control_mode; ArduPilot has none (the commands are its liveness)
};
Autopilot px4Autopilot();
Autopilot ardupilotAutopilot();

struct BridgeConfig {
  double stale_after_s = 0.3;
  double agent_lost_after_s = 1.0;
  double attitude_lost_after_s = 0.5;
  double heartbeat_period_s = 0.05;  // 20 Hz when no command comes (PX4 needs 2 Hz)
  double max_speed_mps = 5.0;        // faster commands are clamped to this, and counted
  double max_yaw_rate_radps = 1.0;   // so are faster turns (the agent's default limit is 0.5)
  Autopilot autopilot = px4Autopilot();
  bool engage = false;
  double engage_after_s = 1.0;
  double engage_retry_s = 1.0;
};

enum class Link {
  kNoAttitude,    // nothing from the vehicle yet
  kNoAgent,       // the vehicle's attitude forwarded, no command accepted yet: no stream
  kFresh,         // streaming the agent's commands
  kStale,         // streaming zero velocity
  kAgentLost,     // stream stopped: no command for agent_lost_after_s
  kAttitudeLost,  // stream stopped: the vehicle silent for attitude_lost_after_s
};
const char* linkName(Link link);

enum class VehicleRequest { kArm, kControlMode };

struct Setpoint {
  std::uint64_t timestamp_us = 0;  // the vehicle timestamp of the attitude sample it answers
  NedVelocity velocity;
  double yawspeed_radps = 0.0;  // about NED down (clockwise from above, PX4's yawspeed); 0 holds the heading
};

// What to publish now.
struct Outbox {
  std::optional<Setpoint> setpoint;
  std::optional<std::uint64_t> heartbeat_us;  // PX4: an offboard_control_mode (velocity) with this timestamp
  std::optional<VehicleRequest> request;
};

struct BridgeCounters {
  std::uint64_t attitude_in = 0, attitude_rejected = 0, attitude_out_of_order = 0, clock_restarts = 0;
  std::uint64_t commands_in = 0, commands_applied = 0, commands_replayed = 0, commands_not_newer = 0;
  std::uint64_t commands_unknown_sample = 0, commands_nonfinite = 0, commands_clamped = 0;
  std::uint64_t setpoints_out = 0, heartbeats_out = 0, requests_out = 0;
};

class BridgeCore {
 public:
  explicit BridgeCore(const BridgeConfig& config);

  // The vehicle's attitude (PX4: vehicle_attitude; ArduPilot: the IMU message's orientation): the IMU sample for the
  // agent, or nullopt if rejected (not a unit quaternion, not newer than the last one; counted). A timestamp more
  // than a second behind the newest is the vehicle's clock restarted, and one ahead of it by more than now_s saw pass
  // plus a day is the clock set (ArduPilot: boot time -> UTC): both accepted, and the commands of the old timeline
  // are forgotten.
  // With `force_frd`, the accelerometer's specific force in FRD body axes read with this attitude, the sample
  // carries the accelerometer (FLU body, the same attitude) for an agent that fuses it (focal.imu_source).
  std::optional<agent::ImuSample> onAttitude(std::uint64_t timestamp_us, const Quaternion& q, double now_s,
                                             const std::optional<ardupilot::SpecificForce>& force_frd = std::nullopt);
  // The agent's command (cmd_vel): its setpoint and heartbeat to send at once, or nothing if it is not accepted.
  Outbox onCommand(const agent::VelocityCommand& command, double now_s);
  // The vehicle's state (PX4: vehicle_status's arming_state ARMED and nav_state; ArduPilot: status's armed and mode).
  void onStatus(bool armed, std::uint8_t mode);
  // Call after every attitude sample and periodically (at least every heartbeat period): stale and lost commands,
  // the heartbeat, the engage requests.
  Outbox tick(double now_s);

  Link link() const { return link_; }
  const BridgeCounters& counters() const { return counters_; }
  const Autopilot& autopilot() const { return config_.autopilot; }
  bool armed() const { return armed_.value_or(false); }
  std::optional<std::uint8_t> mode() const { return mode_; }
  // The vehicle's timestamp of the newest attitude sample forwarded.
  std::optional<std::uint64_t> newestTimestampUs() const { return newest_us_; }
  // State changes since the last call, one line each, for the log and the diagnostics topic.
  std::vector<std::string> takeEvents();

 private:
  Link evaluate(double now_s) const;
  void note(std::string event) { events_.push_back(std::move(event)); }
  void sent(Outbox& out, double now_s);

  BridgeConfig config_;
  Link link_ = Link::kNoAttitude;
  BridgeCounters counters_;
  std::vector<std::string> events_;
  std::optional<std::uint64_t> first_us_, newest_us_;  // attitude timestamps forwarded
  double newest_at_s_ = 0.0;
  std::optional<std::uint64_t> applied_us_;  // the sample the newest applied command answers
  double last_heartbeat_s_ = 0.0;
  std::optional<std::uint64_t> streaming_since_us_;
  std::optional<std::uint64_t> last_request_us_;
  std::optional<bool> armed_;
  std::optional<std::uint8_t> mode_;
};

}  // namespace swa::autopilot
