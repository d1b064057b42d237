#include "swa/sim/imu_model.h"

#include "swa/sim/timing.h"

namespace swa::sim {

ImuModel::ImuModel(const ImuSetup& setup, double q_c_mps2, Rng bias_rng, Rng noise_rng)
    : setup_(setup), q_c_mps2_(q_c_mps2), noise_rng_(noise_rng) {
  const double bx = bias_rng.normal();
  const double by = bias_rng.normal();
  bias_body_mps2_ = setup_.bias_std * agent::Vec2(bx, by);
}

agent::ImuSample ImuModel::sample(agent::StampNs stamp_ns, const agent::Vec2& acceleration_mps2, double heading_rad) {
  const double nx = noise_rng_.normal();
  const double ny = noise_rng_.normal();
  const double nh = noise_rng_.normal();
  const agent::Vec2 body = agent::rotation(-heading_rad) * acceleration_mps2 + bias_body_mps2_ +
                           setup_.noise_std * agent::Vec2(nx, ny);
  agent::ImuSample imu;
  imu.stamp_ns = stamp_ns;
  imu.pitch_rad = body.x() / q_c_mps2_;
  imu.roll_rad = body.y() / q_c_mps2_;
  imu.heading_rad = wrapAngle(heading_rad + setup_.heading_noise_std_rad * nh);
  return imu;
}

}  // namespace swa::sim
