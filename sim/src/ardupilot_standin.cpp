#include "swa/sim/ardupilot_standin.h"

#include <cmath>
#include <cstdio>
#include <utility>

namespace swa::sim {

ArdupilotStandin::ArdupilotStandin(double guid_timeout_s)
    : timeout_ns_(static_cast<agent::StampNs>(std::llround(guid_timeout_s * 1e9))) {}

void ArdupilotStandin::cmdVel(agent::StampNs now, bool map_frame, const ardupilot::EnuTwist& twist) {
  if (!map_frame) {
    if (!other_frame_reported_) {
      events_.emplace_back("a cmd_vel in a frame other than \"map\" is not simulated: dropped");
      other_frame_reported_ = true;
    }
    return;
  }
  if (mode_ != ardupilot::kModeGuided || !armed_) return;  // ArduPilot drops it without an answer
  if (timed_out_) events_.emplace_back("cmd_vel again: following it");
  timed_out_ = false;
  last_cmd_ns_ = now;
  twist_ = twist;
}

bool ArdupilotStandin::armMotors(bool arm) {
  if (arm != armed_) events_.emplace_back(arm ? "armed on request" : "disarmed on request");
  armed_ = arm;
  return true;
}

ArdupilotStandin::ModeReply ArdupilotStandin::modeSwitch(std::uint8_t mode) {
  const bool simulated = mode == ardupilot::kModeGuided || mode == ardupilot::kModeLoiter ||
                         mode == ardupilot::kModeBrake;
  if (simulated && mode != mode_) {
    events_.push_back(std::string(ardupilot::copterModeName(mode)) + " on request");
    mode_ = mode;
    last_cmd_ns_.reset();  // GUIDED starts from a stop until the first cmd_vel
    timed_out_ = false;
  }
  return ModeReply{simulated, mode_};
}

ArdupilotStandin::Decision ArdupilotStandin::step(agent::StampNs now) {
  Decision d;
  if (mode_ != ardupilot::kModeGuided || !armed_ || !last_cmd_ns_ || timed_out_) return d;
  if (now - *last_cmd_ns_ > timeout_ns_) {
    silent_for_s_ = static_cast<double>(now - *last_cmd_ns_) * 1e-9;
    char text[160];
    std::snprintf(text, sizeof text, "no cmd_vel for %.2f s (GUID_TIMEOUT): stopping, holding in GUIDED",
                  silent_for_s_);
    events_.emplace_back(text);
    timed_out_ = true;
    return d;
  }
  d.velocity_mps = ardupilot::stableVelocityOf(twist_);
  d.yaw_rate_radps = twist_.yaw_rate_radps;
  d.following = agent::isFinite(d.velocity_mps) && std::isfinite(d.yaw_rate_radps);
  if (!d.following) d = Decision{};
  return d;
}

std::vector<std::string> ArdupilotStandin::takeEvents() { return std::exchange(events_, {}); }

}  // namespace swa::sim
