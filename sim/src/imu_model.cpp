#include "swa/sim/imu_model.h"

#include <cmath>

#include "swa/sim/timing.h"

namespace swa::sim {

ImuModel::ImuModel(const ImuSetup& setup, double q_c_mps2, Rng bias_rng, Rng noise_rng, Rng walk_rng)
    : setup_(setup), q_c_mps2_(q_c_mps2), noise_rng_(noise_rng), walk_rng_(walk_rng) {
  const double bx = bias_rng.normal();
  const double by = bias_rng.normal();
  bias_body_mps2_ = setup_.bias_std * agent::Vec2(bx, by);
  // After the acceleration bias's two draws, so that those stay what they were before the compass had a bias.
  heading_bias_rad_ = setup_.heading_bias_std_rad * bias_rng.normal();
}

agent::ImuSample ImuModel::sample(agent::StampNs stamp_ns, const agent::Vec2& acceleration_mps2, double heading_rad) {
  const double nx = noise_rng_.normal();
  const double ny = noise_rng_.normal();
  const double nh = noise_rng_.normal();
  if (setup_.heading_bias_walk_radps > 0.0) {
    if (last_stamp_ns_ && stamp_ns > *last_stamp_ns_) {
      const double dt_s = static_cast<double>(stamp_ns - *last_stamp_ns_) * 1e-9;
      heading_bias_rad_ += setup_.heading_bias_walk_radps * std::sqrt(dt_s) * walk_rng_.normal();
    }
    last_stamp_ns_ = stamp_ns;
  }
  const agent::Vec2 body = agent::rotation(-heading_rad) * acceleration_mps2 + bias_body_mps2_ +
                           setup_.noise_std * agent::Vec2(nx, ny);
  agent::ImuSample imu;
  imu.stamp_ns = stamp_ns;
  imu.pitch_rad = body.x() / q_c_mps2_;
  imu.roll_rad = body.y() / q_c_mps2_;
  imu.heading_rad = wrapAngle(heading_rad + heading_bias_rad_ + setup_.heading_noise_std_rad * nh);
  return imu;
}

}  // namespace swa::sim
