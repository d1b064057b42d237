#include "swa/sim/uav_dynamics.h"

#include <algorithm>

namespace swa::sim {

void stepLateral(const DynamicsSetup& setup, double dt_s, const agent::Vec2& velocity_setpoint_mps,
                 const agent::Vec2& disturbance_mps2, KinematicState& state) {
  const double lag_s = std::max(setup.velocity_lag_s, dt_s);
  const agent::Vec2 commanded = (velocity_setpoint_mps - state.velocity_mps) / lag_s + disturbance_mps2;
  const agent::Vec2 v_old = state.velocity_mps;
  agent::Vec2 v_new = v_old + commanded * dt_s;
  const double speed = v_new.norm();
  if (speed > setup.speed_limit_mps) v_new *= setup.speed_limit_mps / speed;
  state.acceleration_mps2 = (v_new - v_old) / dt_s;
  state.position_m += 0.5 * (v_old + v_new) * dt_s;
  state.velocity_mps = v_new;
}

}  // namespace swa::sim
