#include "swa/sim/px4_standin.h"

#include <cmath>
#include <cstdio>
#include <utility>

#include "swa/px4/vehicle.h"

namespace swa::sim {

Px4Standin::Px4Standin(double offboard_loss_timeout_s, const std::optional<Px4EstimatorParams>& ekf)
    : loss_timeout_ns_(static_cast<agent::StampNs>(std::llround(offboard_loss_timeout_s * 1e9))),
      arming_state_(px4::kArmingStateArmed),
      nav_state_(px4::kNavStateAutoLoiter) {
  if (ekf) ekf_.emplace(*ekf);
}

void Px4Standin::gnss(agent::StampNs now, bool fix) {
  if (!ekf_) return;
  ekf_->gnss(now, fix);
  // At once, not at the next step: the local position published with this fix carries what EKF2 makes of it (the
  // first one too, or a vehicle flying on GNSS since its takeoff would say invalid at the run's start).
  ekf_->update(now);
}

void Px4Standin::visualOdometry(agent::StampNs now, bool position, bool velocity) {
  if (ekf_) ekf_->externalVision(now, position, velocity);
}

double Px4Standin::deadReckoningS(agent::StampNs now) const {
  return dead_reckoning_since_ns_ ? static_cast<double>(now - *dead_reckoning_since_ns_) * 1e-9 : 0.0;
}

void Px4Standin::lose(std::uint8_t nav_state, const char* text) {
  events_.push_back({StandinEvent::Control::kLost, text});
  nav_state_ = nav_state;
  failsafe_ = true;
}

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
  // ... and velocity setpoints without a valid local velocity (offboardCheck.cpp)
  if (velocity_control_ && !localPositionValid()) return kTemporarilyRejected;
  if (nav_state_ != px4::kNavStateOffboard) {
    events_.push_back({StandinEvent::Control::kRegained, "OFFBOARD on request (offboard_control_mode streaming)"});
    unsimulated_reported_ = false;
  }
  nav_state_ = px4::kNavStateOffboard;
  failsafe_ = false;
  return kAccepted;
}

Px4Standin::Decision Px4Standin::step(agent::StampNs now) {
  Decision d;
  if (ekf_) {
    ekf_->update(now);
    if (!ekf_->deadReckoning()) dead_reckoning_since_ns_.reset();
    if (ekf_->deadReckoning() && !dead_reckoning_since_ns_) dead_reckoning_since_ns_ = now;
  }
  char text[200];
  if (nav_state_ == px4::kNavStateAutoLoiter && failsafe_ && !localPositionValid()) {
    lost_after_s_ = deadReckoningS(now);
    std::snprintf(text, sizeof text,
                  "Hold without a position after %.2f s of dead reckoning without GNSS or external vision "
                  "(EKF2_NOAID_TOUT): failsafe, Descend (RTL and Land need a position)",
                  lost_after_s_);
    lose(px4::kNavStateDescend, text);
    return d;
  }
  if (nav_state_ != px4::kNavStateOffboard) return d;
  if (!signalFresh(now)) {
    lost_after_s_ = last_heartbeat_ns_ ? static_cast<double>(now - *last_heartbeat_ns_) * 1e-9 : 0.0;
    std::snprintf(text, sizeof text,
                  "offboard lost: no offboard_control_mode for %.2f s (COM_OF_LOSS_T): failsafe, holding (Hold)",
                  lost_after_s_);
    lose(px4::kNavStateAutoLoiter, text);
    return d;
  }
  if (velocity_control_ && !localPositionValid()) {
    lost_after_s_ = deadReckoningS(now);
    std::snprintf(text, sizeof text,
                  "offboard lost: local velocity invalid after %.2f s of dead reckoning without GNSS or external "
                  "vision (EKF2_NOAID_TOUT): failsafe, Altitude mode (COM_OBL_RC_ACT Position needs a position)",
                  lost_after_s_);
    lose(px4::kNavStateAltctl, text);
    return d;
  }
  if (!setpoint_) return d;  // in OFFBOARD before the first setpoint: hold
  if (!velocity_control_ || !setpoint_velocity_only_) {
    if (!unsimulated_reported_) {
      events_.push_back({StandinEvent::Control::kNone,
                         "a setpoint other than velocity-only (position set, or control mode not velocity) is not "
                         "simulated: holding"});
      unsimulated_reported_ = true;
    }
    return d;
  }
  d.velocity_mps = px4::stableOf(*setpoint_);
  d.following = agent::isFinite(d.velocity_mps);
  if (!d.following) d.velocity_mps = agent::Vec2::Zero();
  return d;
}

std::vector<StandinEvent> Px4Standin::takeEvents() { return std::exchange(events_, {}); }

}  // namespace swa::sim
