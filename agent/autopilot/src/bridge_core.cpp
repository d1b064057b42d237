#include "swa/autopilot/bridge_core.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "swa/autopilot/ardupilot.h"
#include "swa/px4/vehicle.h"

namespace swa::autopilot {
namespace {

using px4::eulerOf;
using px4::isAttitude;
using px4::nedOf;
using px4::stampNsOf;
using px4::SwaAttitude;
using px4::swaAttitude;
using px4::timestampUsOf;
using px4::yawspeedOf;

constexpr std::uint64_t kClockRestartUs = 1'000'000;  // a timestamp this far behind the newest: the vehicle restarted
// One this far ahead of the newest, beyond the time that passed: its clock was set (boot time -> UTC is decades). A
// day, not a second: a simulator running faster than real time (ArduPilot SITL --speedup) jumps by seconds in a pause.
constexpr std::uint64_t kClockSetUs = 86'400'000'000;

// Durations compared in whole microseconds, on the vehicle's clock: exact at the thresholds.
std::uint64_t microseconds(double seconds) { return static_cast<std::uint64_t>(std::llround(seconds * 1e6)); }
// to - from, 0 if `to` is not later.
std::uint64_t elapsedUs(std::uint64_t from_us, std::uint64_t to_us) { return to_us > from_us ? to_us - from_us : 0; }

}  // namespace

Autopilot px4Autopilot() { return Autopilot{"PX4", px4::kNavStateOffboard, "offboard", px4::navStateName, true}; }

Autopilot ardupilotAutopilot() {
  return Autopilot{"ArduPilot", ardupilot::kModeGuided, "GUIDED", ardupilot::copterModeName, false};
}

const char* linkName(Link link) {
  switch (link) {
    case Link::kNoAttitude:
      return "no attitude from the vehicle yet";
    case Link::kNoAgent:
      return "waiting for the agent's first command";
    case Link::kFresh:
      return "streaming the agent's commands";
    case Link::kStale:
      return "command stale: streaming zero velocity";
    case Link::kAgentLost:
      return "agent lost: stream stopped (the autopilot's own failsafe takes over)";
    case Link::kAttitudeLost:
      return "vehicle silent: stream stopped";
  }
  return "?";
}

BridgeCore::BridgeCore(const BridgeConfig& config) : config_(config) {}

std::optional<agent::ImuSample> BridgeCore::onAttitude(std::uint64_t timestamp_us, const Quaternion& q, double now_s,
                                                       const std::optional<ardupilot::SpecificForce>& force_frd) {
  ++counters_.attitude_in;
  const std::optional<agent::StampNs> stamp = stampNsOf(timestamp_us);
  if (!isAttitude(q) || !stamp) {
    ++counters_.attitude_rejected;
    return std::nullopt;
  }
  // A jump ahead by more than the local clock saw pass plus a day: ArduPilot's stamps go from time-since-boot to UTC
  // when its clock is set. Kept, the commands of the old timeline would look a lifetime old and stop the stream
  // (agent lost) until the agent answered a new sample.
  const bool jumped_ahead =
      newest_us_ && timestamp_us > *newest_us_ &&
      timestamp_us - *newest_us_ > microseconds(std::max(now_s - newest_at_s_, 0.0)) + kClockSetUs;
  if (newest_us_ && (timestamp_us <= *newest_us_ || jumped_ahead)) {
    if (!jumped_ahead && *newest_us_ - timestamp_us < kClockRestartUs) {
      ++counters_.attitude_out_of_order;
      return std::nullopt;
    }
    ++counters_.clock_restarts;
    note(std::string(config_.autopilot.name) + "'s clock " + (jumped_ahead ? "jumped ahead" : "restarted") +
         " (attitude stamp " + std::to_string(timestamp_us) + " us after " + std::to_string(*newest_us_) +
         " us): the old timeline's commands are forgotten");
    first_us_.reset();
    applied_us_.reset();
    streaming_since_us_.reset();
    last_request_us_.reset();
  }
  if (!first_us_) first_us_ = timestamp_us;
  newest_us_ = timestamp_us;
  newest_at_s_ = now_s;
  const SwaAttitude a = swaAttitude(eulerOf(q));
  agent::ImuSample imu{*stamp, a.roll_rad, a.pitch_rad, a.heading_rad};
  if (force_frd) {
    // FRD -> FLU; the attitude's roll and pitch are SWA's tilt angles exactly (px4/frames.h: flippedBody), so the
    // agent turns the force level with the same rotation the vehicle has.
    agent::AccelerometerSample acc;
    acc.specific_force_body_mps2 = px4::flippedBody(agent::Vec3(force_frd->x, force_frd->y, force_frd->z));
    acc.roll_rad = a.roll_rad;
    acc.pitch_rad = a.pitch_rad;
    imu.accelerometer = acc;
  }
  return imu;
}

Outbox BridgeCore::onCommand(const agent::VelocityCommand& command, double now_s) {
  ++counters_.commands_in;
  Outbox out;
  if (!agent::isFinite(command.velocity_mps) || !std::isfinite(command.yaw_rate_radps)) {
    ++counters_.commands_nonfinite;
    return out;
  }
  const std::optional<std::uint64_t> answered = timestampUsOf(command.answered_stamp_ns);
  if (!answered || !first_us_ || *answered < *first_us_) {
    ++counters_.commands_replayed;  // answers a sample from before this bridge (or PX4's clock) started
    return out;
  }
  if (*answered > *newest_us_) {
    ++counters_.commands_unknown_sample;  // answers a sample this bridge never forwarded
    return out;
  }
  if (applied_us_ && *answered <= *applied_us_) {
    ++counters_.commands_not_newer;
    return out;
  }
  agent::Vec2 v = command.velocity_mps;
  double yaw_rate = command.yaw_rate_radps;
  const bool too_fast = v.norm() > config_.max_speed_mps;
  const bool turns_too_fast = std::abs(yaw_rate) > config_.max_yaw_rate_radps;
  if (too_fast) v *= config_.max_speed_mps / v.norm();
  if (turns_too_fast) yaw_rate = std::copysign(config_.max_yaw_rate_radps, yaw_rate);
  if (too_fast || turns_too_fast) ++counters_.commands_clamped;
  ++counters_.commands_applied;
  applied_us_ = *answered;
  out.setpoint = Setpoint{*answered, nedOf(v), yawspeedOf(yaw_rate)};
  if (config_.autopilot.heartbeat) out.heartbeat_us = *answered;
  sent(out, now_s);
  return out;
}

void BridgeCore::onStatus(bool armed, std::uint8_t mode) {
  const Autopilot& a = config_.autopilot;
  if (armed_ != armed) note(std::string(a.name) + (armed ? ": armed" : ": not armed"));
  if (mode_ != mode) {
    const auto name = [&](std::uint8_t m) { return a.mode_name ? a.mode_name(m) : "?"; };
    note(std::string(a.name) + ": mode " + (mode_ ? name(*mode_) : "unknown") + " -> " + name(mode) + " (" +
         std::to_string(mode) + ")");
  }
  armed_ = armed;
  mode_ = mode;
}

Link BridgeCore::evaluate(double now_s) const {
  if (!newest_us_) return Link::kNoAttitude;
  if (now_s - newest_at_s_ > config_.attitude_lost_after_s) return Link::kAttitudeLost;
  if (!applied_us_) return link_ == Link::kAgentLost ? Link::kAgentLost : Link::kNoAgent;
  const std::uint64_t age_us = elapsedUs(*applied_us_, *newest_us_);
  if (age_us <= microseconds(config_.stale_after_s)) return Link::kFresh;
  if (age_us <= microseconds(config_.agent_lost_after_s)) return Link::kStale;
  return Link::kAgentLost;
}

Outbox BridgeCore::tick(double now_s) {
  Outbox out;
  const Link now = evaluate(now_s);
  const bool streaming = now == Link::kFresh || now == Link::kStale;
  if (now != link_) {
    note(std::string("link: ") + linkName(now));
    // Stop and hover, holding the heading (yawspeed 0, not the stale command's rate). Stamped with the sample the last
    // command answered: PX4 takes it as a setpoint of that moment, and it answers no new sample (a receiver that
    // waits for answers, the simulator, does not mistake it for one).
    if (now == Link::kStale) out.setpoint = Setpoint{*applied_us_, NedVelocity{}, 0.0};
    link_ = now;
  }
  if (!streaming) {
    streaming_since_us_.reset();
    return out;
  }
  if (!streaming_since_us_) streaming_since_us_ = *newest_us_;
  const bool keep_alive_due = now_s - last_heartbeat_s_ >= config_.heartbeat_period_s;
  if (config_.autopilot.heartbeat && (out.setpoint || keep_alive_due)) {
    out.heartbeat_us = 0;
  } else if (!config_.autopilot.heartbeat && now == Link::kStale && !out.setpoint && keep_alive_due) {
    // No heartbeat keeps a lone zero setpoint alive (a best-effort sample may be lost, and ArduPilot would fly the
    // last command until GUID_TIMEOUT): repeat it at the heartbeat's period while stale.
    out.setpoint = Setpoint{*applied_us_, NedVelocity{}, 0.0};
  }
  if (out.setpoint || out.heartbeat_us) sent(out, now_s);
  // Engage only on the agent's own commands, with the stream established in vehicle time and the state known.
  if (!config_.engage || now != Link::kFresh || !armed_ || !mode_) return out;
  if (elapsedUs(*streaming_since_us_, *newest_us_) < microseconds(config_.engage_after_s)) return out;
  if (last_request_us_ && elapsedUs(*last_request_us_, *newest_us_) < microseconds(config_.engage_retry_s)) return out;
  if (!*armed_) {
    out.request = VehicleRequest::kArm;
  } else if (*mode_ != config_.autopilot.control_mode) {
    out.request = VehicleRequest::kControlMode;
  } else {
    return out;
  }
  last_request_us_ = *newest_us_;
  ++counters_.requests_out;
  note(out.request == VehicleRequest::kArm
           ? std::string("engage: requesting arm")
           : std::string("engage: requesting ") + config_.autopilot.control_mode_name + " mode");
  return out;
}

void BridgeCore::sent(Outbox& out, double now_s) {
  if (out.setpoint) ++counters_.setpoints_out;
  if (out.heartbeat_us) ++counters_.heartbeats_out;
  // What keeps the stream alive: PX4's heartbeat, or without one the setpoint itself.
  if (out.heartbeat_us || (out.setpoint && !config_.autopilot.heartbeat)) last_heartbeat_s_ = now_s;
}

std::vector<std::string> BridgeCore::takeEvents() { return std::exchange(events_, {}); }

}  // namespace swa::autopilot
