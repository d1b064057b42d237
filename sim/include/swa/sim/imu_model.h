#pragma once
// IMU + magnetometer of one UAV (DESIGN §4): attitude reported as the tilt a multirotor must hold to produce its
// lateral acceleration, in the agent's convention (DESIGN §3.4, agent.cpp): body acceleration = q_c [pitch, roll],
// stable acceleration = R(psi) body acceleration. The error is modelled on the derived acceleration, which is what
// the agent's R_a describes: a constant per-UAV bias plus white noise, both fixed to the airframe (body frame),
// because tilt errors come from sensor and thrust misalignment that turn with the UAV. For a UAV that does not turn
// this is statistically the same as adding them in the stable frame (both are isotropic).
// The heading is the true one plus the compass's bias (a constant per UAV, drawn with the acceleration bias, plus a
// random walk of its own stream, so that an ideal compass leaves every other draw as it was) and white noise.

#include <optional>

#include "swa/agent/geometry.h"
#include "swa/agent/samples.h"
#include "swa/sim/random.h"
#include "swa/sim/scenario.h"

namespace swa::sim {

class ImuModel {
 public:
  // Draws the biases from bias_rng at construction; noise_rng feeds the tilt and heading noise of every sample,
  // walk_rng the heading bias's random walk.
  ImuModel(const ImuSetup& setup, double q_c_mps2, Rng bias_rng, Rng noise_rng, Rng walk_rng);

  // acceleration in the stable/world frame, heading the true heading.
  agent::ImuSample sample(agent::StampNs stamp_ns, const agent::Vec2& acceleration_mps2, double heading_rad);

  const agent::Vec2& bias_body_mps2() const { return bias_body_mps2_; }
  // The compass's bias at the last sample [rad].
  double heading_bias_rad() const { return heading_bias_rad_; }

 private:
  ImuSetup setup_;
  double q_c_mps2_;
  Rng noise_rng_;
  Rng walk_rng_;
  agent::Vec2 bias_body_mps2_;
  double heading_bias_rad_ = 0.0;
  std::optional<agent::StampNs> last_stamp_ns_;
};

}  // namespace swa::sim
