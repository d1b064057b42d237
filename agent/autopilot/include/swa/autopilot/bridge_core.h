#pragma once
// The autopilot bridge of one UAV without DDS (agent/px4_bridge is the process around it): PX4's attitude in, SWA's
// IMU sample out; SWA's velocity commands in, PX4's offboard stream out. Time is an input: PX4's timestamps (the
// vehicle's clock) for everything about commands, and a monotonic local clock `now_s` for the two things only it can
// tell (that PX4 went quiet, and the heartbeat's period).
//
// The offboard stream (offboard_control_mode "velocity" + trajectory_setpoint, deploy/README.md):
//   - every accepted command is sent at once, stamped with the PX4 timestamp of the attitude sample it answers, its
//     yaw rate as PX4's yawspeed (yaw NaN: PX4 follows the rate; 0 holds the heading);
//   - a command older than stale_after_s (vehicle time: newest attitude - the sample it answers) becomes zero
//     velocity and yawspeed 0, stamped like that command (it answers no new sample): the vehicle stops and hovers,
//     holding its heading, while the agent may still recover;
//   - no command for agent_lost_after_s, or no attitude from PX4 for attitude_lost_after_s, stops the stream: PX4's own
//     offboard-loss failsafe (COM_OF_LOSS_T, COM_OBL_RC_ACT) takes over. The bridge never decides a failsafe itself;
//   - otherwise the heartbeat is repeated every heartbeat_period_s, stamped 0 (PX4 stamps it on receipt).
// Commands are accepted only if they answer a sample this bridge forwarded (not one from before it started: a
// restarted bridge is sent its writer's last command again) and are newer than the last one applied.
// It arms and requests offboard only with `engage` (bench tests, the simulator), once the stream has run for
// engage_after_s of vehicle time, and again at most every engage_retry_s while the vehicle is not armed / not offboard.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "swa/agent/samples.h"
#include "swa/px4/frames.h"

namespace swa::px4 {

struct BridgeConfig {
  double stale_after_s = 0.3;
  double agent_lost_after_s = 1.0;
  double attitude_lost_after_s = 0.5;
  double heartbeat_period_s = 0.05;  // 20 Hz when no command comes (PX4 needs 2 Hz)
  double max_speed_mps = 5.0;        // faster commands are clamped to this, and counted
  double max_yaw_rate_radps = 1.0;   // so are faster turns (the agent's default limit is 0.5)
  bool engage = false;
  double engage_after_s = 1.0;
  double engage_retry_s = 1.0;
};

enum class Link {
  kNoAttitude,    // nothing from PX4 yet
  kNoAgent,       // PX4's attitude forwarded, no command accepted yet: no stream
  kFresh,         // streaming the agent's commands
  kStale,         // streaming zero velocity
  kAgentLost,     // stream stopped: no command for agent_lost_after_s
  kAttitudeLost,  // stream stopped: PX4 silent for attitude_lost_after_s
};
const char* linkName(Link link);

enum class VehicleRequest { kArm, kOffboard };

struct Setpoint {
  std::uint64_t timestamp_us = 0;  // the PX4 timestamp of the attitude sample it answers
  NedVelocity velocity;
  double yawspeed_radps = 0.0;  // PX4's yawspeed (about NED down, clockwise from above); 0 holds the heading
};

// What to publish now.
struct Outbox {
  std::optional<Setpoint> setpoint;
  std::optional<std::uint64_t> heartbeat_us;  // an offboard_control_mode (velocity) with this timestamp
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

  // PX4's attitude (vehicle_attitude): the IMU sample for the agent, or nullopt if rejected (not a unit quaternion,
  // not newer than the last one; counted). A timestamp more than a second behind the newest is PX4's clock restarted:
  // accepted, and the commands of the old timeline are forgotten.
  std::optional<agent::ImuSample> onAttitude(std::uint64_t timestamp_us, const Quaternion& q, double now_s);
  // The agent's command (cmd_vel): its setpoint and heartbeat to send at once, or nothing if it is not accepted.
  Outbox onCommand(const agent::VelocityCommand& command, double now_s);
  // PX4's vehicle_status.
  void onStatus(std::uint8_t arming_state, std::uint8_t nav_state);
  // Call after every attitude sample and periodically (at least every heartbeat period): stale and lost commands,
  // the heartbeat, the engage requests.
  Outbox tick(double now_s);

  Link link() const { return link_; }
  const BridgeCounters& counters() const { return counters_; }
  bool armed() const { return arming_state_ == kArmed; }
  std::optional<std::uint8_t> navState() const { return nav_state_; }
  // PX4's timestamp of the newest attitude sample forwarded.
  std::optional<std::uint64_t> newestTimestampUs() const { return newest_us_; }
  // State changes since the last call, one line each, for the log and the diagnostics topic.
  std::vector<std::string> takeEvents();

 private:
  static constexpr std::uint8_t kArmed = 2;
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
  std::optional<std::uint8_t> arming_state_, nav_state_;
};

}  // namespace swa::px4
