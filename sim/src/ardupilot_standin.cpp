#include "swa/sim/ardupilot_standin.h"

#include <cmath>
#include <cstdio>
#include <utility>

namespace swa::sim {

ArdupilotStandin::ArdupilotStandin(double guid_timeout_s, const std::optional<ArdupilotEstimatorParams>& ekf)
    : timeout_ns_(static_cast<agent::StampNs>(std::llround(guid_timeout_s * 1e9))) {
  if (ekf) ekf_.emplace(*ekf);
}

void ArdupilotStandin::gnss(agent::StampNs now, bool fix) {
  if (ekf_) ekf_->gps(now, fix);
}

bool ArdupilotStandin::externalOdometry(agent::StampNs now, agent::StampNs stamp_ns) {
  return ekf_ && ekf_->externalOdometry(now, stamp_ns);
}

void ArdupilotStandin::cmdVel(agent::StampNs now, bool map_frame, const ardupilot::EnuTwist& twist) {
  if (!map_frame) {
    if (!other_frame_reported_) {
      events_.push_back(
          {StandinEvent::Control::kNone, "a cmd_vel in a frame other than \"map\" is not simulated: dropped"});
      other_frame_reported_ = true;
    }
    return;
  }
  if (mode_ != ardupilot::kModeGuided || !armed_) return;  // ArduPilot drops it without an answer
  if (timed_out_) events_.push_back({StandinEvent::Control::kRegained, "cmd_vel again: following it"});
  timed_out_ = false;
  last_cmd_ns_ = now;
  twist_ = twist;
}

bool ArdupilotStandin::armMotors(bool arm) {
  if (arm != armed_)
    events_.push_back({StandinEvent::Control::kNone, arm ? "armed on request" : "disarmed on request"});
  armed_ = arm;
  return true;
}

ArdupilotStandin::ModeReply ArdupilotStandin::modeSwitch(std::uint8_t mode) {
  const bool simulated =
      mode == ardupilot::kModeGuided || mode == ardupilot::kModeLoiter || mode == ardupilot::kModeBrake;
  // A position mode needs a position while armed (Copter::set_mode: "requires position"); the EKF failsafe refuses
  // them all until it clears.
  if (simulated && armed_ && !positionOk()) return ModeReply{false, mode_};
  if (simulated && mode != mode_) {
    events_.push_back({mode == ardupilot::kModeGuided ? StandinEvent::Control::kRegained : StandinEvent::Control::kLost,
                       std::string(ardupilot::copterModeName(mode)) + " on request"});
    mode_ = mode;
    last_cmd_ns_.reset();  // GUIDED starts from a stop until the first cmd_vel
    timed_out_ = false;
  }
  return ModeReply{simulated, mode_};
}

ArdupilotStandin::Decision ArdupilotStandin::step(agent::StampNs now) {
  Decision d;
  if (ekf_) {
    ekf_->update(now);
    if (ekf_->ekfFailsafe() && armed_ && mode_ != ardupilot::kModeLand) {
      events_.push_back({StandinEvent::Control::kLost,
                         std::string("EKF failsafe: no position for 1 s (7 s after the last GPS fix or external "
                                     "navigation): FS_EKF_ACTION LAND from ") +
                             ardupilot::copterModeName(mode_)});
      mode_ = ardupilot::kModeLand;
    }
  }
  if (mode_ != ardupilot::kModeGuided || !armed_ || !last_cmd_ns_ || timed_out_) return d;
  if (now - *last_cmd_ns_ > timeout_ns_) {
    silent_for_s_ = static_cast<double>(now - *last_cmd_ns_) * 1e-9;
    char text[160];
    std::snprintf(text, sizeof text, "no cmd_vel for %.2f s (GUID_TIMEOUT): stopping, holding in GUIDED",
                  silent_for_s_);
    events_.push_back({StandinEvent::Control::kLost, text});
    timed_out_ = true;
    return d;
  }
  d.velocity_mps = ardupilot::stableVelocityOf(twist_);
  d.yaw_rate_radps = twist_.yaw_rate_radps;
  d.following = agent::isFinite(d.velocity_mps) && std::isfinite(d.yaw_rate_radps);
  if (!d.following) d = Decision{};
  return d;
}

std::vector<StandinEvent> ArdupilotStandin::takeEvents() { return std::exchange(events_, {}); }

}  // namespace swa::sim
