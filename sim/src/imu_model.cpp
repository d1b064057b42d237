#include "swa/sim/imu_model.h"

#include <cmath>

#include "swa/sim/timing.h"

namespace swa::sim {

namespace {

// The attitude whose body z axis points along the thrust (T_x, T_y, g) in the level frame, in tiltRotation()'s
// convention: z = (sin pitch cos roll, sin roll, cos pitch cos roll).
void thrustTilt(const agent::Vec2& thrust_level_mps2, double& roll_rad, double& pitch_rad) {
  const agent::Vec3 z =
      agent::Vec3(thrust_level_mps2.x(), thrust_level_mps2.y(), agent::kStandardGravity_mps2).normalized();
  roll_rad = std::asin(z.y());
  pitch_rad = std::atan2(z.x(), z.z());
}

}  // namespace

ImuModel::ImuModel(const ImuSetup& setup, double q_c_mps2, Streams streams)
    : setup_(setup),
      q_c_mps2_(q_c_mps2),
      noise_rng_(streams.noise),
      walk_rng_(streams.walk),
      accel_noise_rng_(streams.accel_noise) {
  const double bx = streams.bias.normal();
  const double by = streams.bias.normal();
  bias_body_mps2_ = setup_.bias_std * agent::Vec2(bx, by);
  // After the acceleration bias's two draws, so that those stay what they were before the compass had a bias.
  heading_bias_rad_ = setup_.heading_bias_std_rad * streams.bias.normal();
  attitude_error_roll_rad_ = setup_.attitude_error_std_rad * streams.accel_bias.normal();
  attitude_error_pitch_rad_ = setup_.attitude_error_std_rad * streams.accel_bias.normal();
  for (int k = 0; k < 3; ++k) accel_bias_mps2_[k] = setup_.accel_bias_std_mps2 * streams.accel_bias.normal();
}

agent::ImuSample ImuModel::sample(agent::StampNs stamp_ns, const agent::Vec2& acceleration_mps2,
                                  const agent::Vec2& thrust_mps2, double heading_rad) {
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
  const agent::Mat2 to_level = agent::rotation(-heading_rad);
  const agent::Vec2 thrust_level = to_level * thrust_mps2;
  const agent::Vec2 body = thrust_level + bias_body_mps2_ + setup_.noise_std * agent::Vec2(nx, ny);
  agent::ImuSample imu;
  imu.stamp_ns = stamp_ns;
  imu.pitch_rad = body.x() / q_c_mps2_;
  imu.roll_rad = body.y() / q_c_mps2_;
  imu.heading_rad = wrapAngle(heading_rad + heading_bias_rad_ + setup_.heading_noise_std_rad * nh);

  double roll = 0.0;
  double pitch = 0.0;
  thrustTilt(thrust_level, roll, pitch);
  const agent::Vec2 a_level = to_level * acceleration_mps2;
  // Altitude held: the specific force is (a, +g) in the level frame, read in the body frame the thrust tilts.
  const agent::Vec3 f_level(a_level.x(), a_level.y(), agent::kStandardGravity_mps2);
  const agent::Vec3 noise(accel_noise_rng_.normal(), accel_noise_rng_.normal(), accel_noise_rng_.normal());
  agent::AccelerometerSample acc;
  acc.specific_force_body_mps2 =
      agent::tiltRotation(roll, pitch).transpose() * f_level + accel_bias_mps2_ + setup_.accel_noise_std_mps2 * noise;
  acc.roll_rad = roll + attitude_error_roll_rad_;
  acc.pitch_rad = pitch + attitude_error_pitch_rad_;
  imu.accelerometer = acc;
  return imu;
}

}  // namespace swa::sim
