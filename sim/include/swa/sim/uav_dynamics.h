#pragma once
// Lateral point-mass dynamics of one UAV (DESIGN §4): the autopilot makes velocity follow the setpoint as a
// first-order lag, wind adds an acceleration, and the airframe cannot exceed its speed limit.

#include "swa/agent/geometry.h"
#include "swa/sim/scenario.h"

namespace swa::sim {

struct KinematicState {
  agent::Vec2 position_m = agent::Vec2::Zero();
  agent::Vec2 velocity_mps = agent::Vec2::Zero();
  agent::Vec2 acceleration_mps2 = agent::Vec2::Zero();  // effective acceleration over the last step
};

// One step of dt: a = (v_cmd - v) / lag + disturbance, v += a dt, then |v| clamped to the speed limit. The
// acceleration stored is the one actually achieved, (v_new - v_old) / dt, so that position, velocity, acceleration
// and the IMU tilt derived from it stay mutually consistent when the limit bites. Position uses the trapezoid rule
// (= v dt + a dt^2 / 2). A lag shorter than dt is treated as dt (dead-beat) instead of letting explicit Euler
// overshoot and diverge.
void stepLateral(const DynamicsSetup& setup, double dt_s, const agent::Vec2& velocity_setpoint_mps,
                 const agent::Vec2& disturbance_mps2, KinematicState& state);

}  // namespace swa::sim
