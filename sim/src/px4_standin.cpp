#include "swa/sim/px4_standin.h"

#include <cmath>
#include <cstdio>
#include <utility>

#include "swa/px4/vehicle.h"

namespace swa::sim {

Px4Standin::Px4Standin(double offboard_loss_timeout_s)
    : loss_timeout_ns_(static_cast<agent::StampNs>(std::llround(offboard_loss_timeout_s * 1e9))),
      arming_state_(px4::kArmingStateArmed),
      nav_state_(px4::kNavStateAutoLoiter) {}

bool Px4Standin::signalFresh(agent::StampNs now) const {
  return last_heartbeat_ns_ && now - *last_heartbeat_ns_ <= loss_timeout_ns_;
}

void Px4Standin::offboardControlMode(agent::StampNs now, bool velocity_control) {
  last_heartbeat_ns_ = now;
  velocity_control_ = velocity_control;
}

void Px4Standin::trajectorySetpoint(const px4::NedVelocity& velocity, bool velocity_only) {
  setpoint_ = velocity;
  setpoint_velocity_only_ = velocity_only;
}

std::uint8_t Px4Standin::vehicleCommand(agent::StampNs now, std::uint32_t command, float param1, float param2) {
  constexpr std::uint8_t kAccepted = 0, kTemporarilyRejected = 1, kUnsupported = 3;
  if (command == px4::kCmdComponentArmDisarm) {
    arming_state_ = param1 > 0.5f ? px4::kArmingStateArmed : px4::kArmingStateDisarmed;
    return kAccepted;
  }
  if (command != px4::kCmdDoSetMode || param1 != px4::kModeFlagCustomModeEnabled ||
      param2 != px4::kCustomMainModeOffboard) {
    return kUnsupported;
  }
  if (!signalFresh(now)) return kTemporarilyRejected;  // PX4 refuses offboard without the stream
  if (nav_state_ != px4::kNavStateOffboard) {
    events_.push_back("OFFBOARD on request (offboard_control_mode streaming)");
    unsimulated_reported_ = false;
  }
  nav_state_ = px4::kNavStateOffboard;
  failsafe_ = false;
  return kAccepted;
}

Px4Standin::Decision Px4Standin::step(agent::StampNs now) {
  Decision d;
  if (nav_state_ != px4::kNavStateOffboard) return d;
  if (!signalFresh(now)) {
    lost_after_s_ = last_heartbeat_ns_ ? static_cast<double>(now - *last_heartbeat_ns_) * 1e-9 : 0.0;
    char text[160];
    std::snprintf(text, sizeof text,
                  "offboard lost: no offboard_control_mode for %.2f s (COM_OF_LOSS_T): failsafe, holding (Hold)",
                  lost_after_s_);
    events_.emplace_back(text);
    nav_state_ = px4::kNavStateAutoLoiter;
    failsafe_ = true;
    return d;
  }
  if (!setpoint_) return d;  // in OFFBOARD before the first setpoint: hold
  if (!velocity_control_ || !setpoint_velocity_only_) {
    if (!unsimulated_reported_) {
      events_.emplace_back("a setpoint other than velocity-only (position set, or control mode not velocity) is not "
                           "simulated: holding");
      unsimulated_reported_ = true;
    }
    return d;
  }
  d.velocity_mps = px4::stableOf(*setpoint_);
  d.following = agent::isFinite(d.velocity_mps);
  if (!d.following) d.velocity_mps = agent::Vec2::Zero();
  return d;
}

std::vector<std::string> Px4Standin::takeEvents() { return std::exchange(events_, {}); }

}  // namespace swa::sim
