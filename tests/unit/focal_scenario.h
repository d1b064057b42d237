#pragma once
// The paper's §IV-C tuning scenario as a tiny seeded world: a hovering group of neighbours and one focal UAV whose
// velocity follows a command through a first-order lag (time constant 1 s, as the simulator of DESIGN §4), pushed
// by Ornstein-Uhlenbeck gusts. Sensors: IMU tilt with per-run bias and white noise (derived acceleration noise
// ~ R_a), heading, and identified detections of the group at 10 Hz with R_o noise.

#include <cmath>
#include <random>
#include <vector>

#include "swa/agent/config.h"
#include "swa/agent/samples.h"

namespace swa::agent::testing {

struct FocalWorld {
  struct Options {
    double lag_s = 1.0;
    double gust_std = 0.2;  // m/s^2
    double gust_corr_s = 5.0;
    double acc_bias_std = 0.05;  // m/s^2, constant per run
    double acc_noise_std = 1.5;  // m/s^2 white (sqrt(R_a))
    double det_noise_var = 0.1;  // m^2 (R_o)
    double heading_rad = 0.7;
    double q_c = 6.35;
  };

  FocalWorld(std::uint64_t seed, std::vector<Vec2> group, Vec2 start, Options o)
      : opt(o), rng(seed), neighbours(std::move(group)), p(start) {
    std::normal_distribution<double> n(0.0, 1.0);
    bias = o.acc_bias_std * Vec2(n(rng), n(rng));
  }

  // Advances the world by dt under command u (stable frame).
  void step(double dt, const Vec2& u) {
    std::normal_distribution<double> n(0.0, 1.0);
    const double phi = std::exp(-dt / opt.gust_corr_s);
    gust = phi * gust + opt.gust_std * std::sqrt(1.0 - phi * phi) * Vec2(n(rng), n(rng));
    a = (u - v) / opt.lag_s + gust;
    p += v * dt + 0.5 * a * dt * dt;
    v += a * dt;
  }

  // Tilt consistent with the true acceleration: body acceleration = q_c [pitch, roll] (DESIGN §3.4); and an
  // accelerometer that measures the same acceleration, read with a level attitude, so that either source
  // (focal.imu_source) sees one measurement.
  ImuSample imu(StampNs t) {
    std::normal_distribution<double> n(0.0, 1.0);
    const Vec2 meas = a + bias + opt.acc_noise_std * Vec2(n(rng), n(rng));
    const Vec2 body_acc = rotation(-opt.heading_rad) * meas;
    const Vec2 body = body_acc / opt.q_c;
    AccelerometerSample acc;
    acc.specific_force_body_mps2 = Vec3(body_acc.x(), body_acc.y(), kStandardGravity_mps2);
    return ImuSample{t, body.y(), body.x(), opt.heading_rad, acc};
  }

  DetectionSet detections(StampNs t) {
    std::normal_distribution<double> n(0.0, std::sqrt(opt.det_noise_var));
    DetectionSet set;
    set.stamp_ns = t;
    const Mat2 to_body = rotation(-opt.heading_rad);
    for (std::size_t i = 0; i < neighbours.size(); ++i) {
      const Vec2 rel = to_body * (neighbours[i] - p) + Vec2(n(rng), n(rng));
      set.detections.push_back({static_cast<int>(i), rel, std::nullopt});
    }
    return set;
  }

  Options opt;
  std::mt19937_64 rng;
  std::vector<Vec2> neighbours;
  Vec2 p, v = Vec2::Zero(), a = Vec2::Zero(), gust = Vec2::Zero(), bias;
};

}  // namespace swa::agent::testing
