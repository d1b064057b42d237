#pragma once
// IMU + magnetometer of one UAV (DESIGN §4). Two acceleration outputs in one sample (issue #44):
// - the tilt (roll_rad, pitch_rad): the attitude a multirotor must hold to produce its *thrust* acceleration, in
//   the agent's convention (DESIGN §3.4, agent.cpp): body acceleration = q_c [pitch, roll], stable acceleration =
//   R(psi) body acceleration. The error is modelled on the derived acceleration, which is what the agent's R_a
//   describes: a constant per-UAV bias plus white noise, both fixed to the airframe (body frame), because tilt errors
//   come from sensor and thrust misalignment that turn with the UAV. For a UAV that does not turn this is
//   statistically the same as adding them in the stable frame (both are isotropic). Thrust is what the attitude
//   shows: drag and gusts push the UAV without tilting it.
// - the accelerometer: the specific force in the body frame (every push: thrust, drag, gusts; minus gravity) with
//   the attitude estimate (the true thrust tilt plus a constant per-UAV error), so that R f - g is the kinematic
//   acceleration up to the attitude error (x g), the accelerometer's bias and its noise.
// The heading is the true one plus the compass's bias (a constant per UAV, drawn with the acceleration bias, plus a
// random walk of its own stream, so that an ideal compass leaves every other draw as it was) and white noise.

#include <cstdint>
#include <optional>

#include "swa/agent/geometry.h"
#include "swa/agent/samples.h"
#include "swa/sim/random.h"
#include "swa/sim/scenario.h"

namespace swa::sim {

class ImuModel {
 public:
  struct Streams {
    Rng bias;        // the tilt's and the compass's constant errors, drawn at construction
    Rng noise;       // tilt and heading white noise
    Rng walk;        // the heading bias's random walk
    Rng accel_bias;  // the accelerometer part's constant errors, drawn at construction
    Rng accel_noise;
    // Every stream of UAV `owner` (its index) in run `seed`, each on its own number (random.h).
    static Streams of(std::uint64_t seed, std::uint32_t owner) {
      return {Rng(seed, owner, Stream::kImuBias), Rng(seed, owner, Stream::kImuNoise),
              Rng(seed, owner, Stream::kHeadingWalk), Rng(seed, owner, Stream::kAccelBias),
              Rng(seed, owner, Stream::kAccelNoise)};
    }
  };
  ImuModel(const ImuSetup& setup, double q_c_mps2, Streams streams);

  // In the stable/world frame: the kinematic acceleration and the thrust's share of it (per unit mass, without
  // gravity); heading the true heading.
  agent::ImuSample sample(agent::StampNs stamp_ns, const agent::Vec2& acceleration_mps2, const agent::Vec2& thrust_mps2,
                          double heading_rad);

  const agent::Vec2& bias_body_mps2() const { return bias_body_mps2_; }
  // The compass's bias at the last sample [rad].
  double heading_bias_rad() const { return heading_bias_rad_; }

 private:
  ImuSetup setup_;
  double q_c_mps2_;
  Rng noise_rng_;
  Rng walk_rng_;
  Rng accel_noise_rng_;
  agent::Vec2 bias_body_mps2_;
  double attitude_error_roll_rad_ = 0.0;
  double attitude_error_pitch_rad_ = 0.0;
  agent::Vec3 accel_bias_mps2_ = agent::Vec3::Zero();
  double heading_bias_rad_ = 0.0;
  std::optional<agent::StampNs> last_stamp_ns_;
};

}  // namespace swa::sim
