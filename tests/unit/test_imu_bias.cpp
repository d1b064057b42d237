// IMU-bias removal (DESIGN §3.4): the running mean of the tilt acceleration converges on a constant bias, freezes
// while the UAV is commanded to manoeuvre, and restarts on reset.

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "swa/agent/imu_bias.h"

namespace swa::agent {
namespace {

constexpr StampNs kImuNs = 10'000'000;  // 100 Hz
constexpr double kWindowS = 30.0;
constexpr double kFreezeMps = 0.5;
constexpr double kHoldS = 5.0;

struct Feed {
  ImuBiasRemover remover{kWindowS, kFreezeMps, kHoldS};
  std::mt19937_64 rng{42};
  std::normal_distribution<double> noise{0.0, 1.5};  // the simulator's IMU noise (sqrt of R_a)
  StampNs t = 0;
  Vec2 last_output = Vec2::Zero();

  // `seconds` of 100 Hz samples: bias + truth + white noise, with `command` in force.
  void run(double seconds, const Vec2& bias, const Vec2& command, const Vec2& truth = Vec2::Zero()) {
    const int n = static_cast<int>(std::lround(seconds / 0.01));
    for (int k = 0; k < n; ++k) {
      t += kImuNs;
      last_output = remover.correct(bias + truth + Vec2(noise(rng), noise(rng)), t, command);
    }
  }
};

TEST(ImuBias, ConvergesOnAConstantBiasUnderNoise) {
  // GIVEN a hovering UAV (zero true acceleration, small commands) whose IMU has bias (0.05, -0.15) m/s^2 and the
  // simulator's white noise (1.5 m/s^2 std)
  Feed f;
  const Vec2 bias(0.05, -0.15);
  // WHEN 120 s of samples are averaged with a 30 s window
  f.run(120.0, bias, Vec2(0.1, 0.0));
  // THEN the estimate is within 0.03 m/s^2 of the bias: an exponential mean over 30 s of 1.5 m/s^2 noise at 100 Hz
  // has std 1.5 * sqrt(0.01 / (2 * 30)) = 0.019 m/s^2 per axis
  EXPECT_NEAR(f.remover.bias().x(), bias.x(), 0.03);
  EXPECT_NEAR(f.remover.bias().y(), bias.y(), 0.03);
  EXPECT_FALSE(f.remover.frozen());
  EXPECT_NEAR(f.remover.averagedSeconds(), 120.0 - 0.01, 1e-9);  // the first sample only starts the clock
}

TEST(ImuBias, NoiseFreeBiasIsLearntWithinTheFirstWindow) {
  // GIVEN a noise-free constant bias
  ImuBiasRemover r(kWindowS, kFreezeMps, kHoldS);
  const Vec2 bias(0.2, -0.1);
  StampNs t = 0;
  Vec2 out = Vec2::Zero();
  for (int k = 0; k <= 3000; ++k) out = r.correct(bias, t += kImuNs, Vec2::Zero());  // 30 s
  // THEN after one window the residual is 1.2 %: the first second is an exponential start (1 - e^-1 of the bias),
  // after it the gain dt / t is a running mean, so the residual falls as e^-1 / t
  EXPECT_NEAR((r.bias() - bias).norm() / bias.norm(), std::exp(-1.0) / 30.0, 0.002);
  EXPECT_EQ(out, bias - r.bias());
  // AND after three more windows (now an exponential mean of 30 s) it has fallen by e^-3 more
  for (int k = 0; k < 9000; ++k) r.correct(bias, t += kImuNs, Vec2::Zero());
  EXPECT_LT((r.bias() - bias).norm() / bias.norm(), 0.001);
}

TEST(ImuBias, FrozenWhileCommandedFasterThanTheThresholdAndForTheHoldAfter) {
  // GIVEN a remover that has learnt a bias over 60 s of hover
  Feed f;
  const Vec2 bias(0.1, 0.05);
  f.run(60.0, bias, Vec2::Zero());
  const Vec2 learnt = f.remover.bias();
  // WHEN the UAV is commanded at 1.2 m/s (> 0.5) while truly accelerating at 0.8 m/s^2 for 20 s
  f.run(20.0, bias, Vec2(1.2, 0.0), Vec2(0.8, 0.0));
  // THEN the estimate did not move (still subtracted), and the output carries the true acceleration
  EXPECT_TRUE(f.remover.frozen());
  EXPECT_EQ(f.remover.bias(), learnt);
  EXPECT_NEAR(f.remover.averagedSeconds(), 60.0 - 0.01, 1e-9);
  // WHEN it then brakes at a slow command (0.3 m/s) for 4.9 s, within the 5 s hold
  f.run(4.9, bias, Vec2(0.0, 0.3), Vec2(-0.8, 0.0));
  // THEN the mean is still frozen: braking is part of the manoeuvre
  EXPECT_TRUE(f.remover.frozen());
  EXPECT_EQ(f.remover.bias(), learnt);
  // WHEN the slow command goes on past the hold with the acceleration still there
  f.run(20.0, bias, Vec2(0.0, 0.3), Vec2(-0.8, 0.0));
  // THEN the mean absorbs part of it: the zero-mean prior is broken, which is why freezing exists
  EXPECT_FALSE(f.remover.frozen());
  EXPECT_LT(f.remover.bias().x() - learnt.x(), -0.3);
}

TEST(ImuBias, ResetForgetsTheMean) {
  Feed f;
  f.run(40.0, Vec2(0.3, 0.3), Vec2::Zero());
  ASSERT_GT(f.remover.bias().norm(), 0.3);
  // WHEN the focal filter restarts and the remover is reset
  f.remover.reset();
  // THEN the mean is zero and starts over
  EXPECT_EQ(f.remover.bias(), Vec2::Zero());
  EXPECT_EQ(f.remover.averagedSeconds(), 0.0);
  // AND a new bias of the opposite sign is learnt from scratch in the next 60 s
  f.run(60.0, Vec2(-0.2, 0.1), Vec2::Zero());
  EXPECT_NEAR(f.remover.bias().x(), -0.2, 0.03);
  EXPECT_NEAR(f.remover.bias().y(), 0.1, 0.03);
}

TEST(ImuBias, WindowZeroIsOff) {
  ImuBiasRemover r(0.0, kFreezeMps, kHoldS);
  EXPECT_FALSE(r.enabled());
  for (int k = 1; k <= 100; ++k) EXPECT_EQ(r.correct(Vec2(0.4, -0.2), k * kImuNs, Vec2::Zero()), Vec2(0.4, -0.2));
  EXPECT_EQ(r.bias(), Vec2::Zero());
}

TEST(ImuBias, RepeatedOrOlderStampsOnlySubtract) {
  ImuBiasRemover r(kWindowS, kFreezeMps, kHoldS);
  for (int k = 1; k <= 500; ++k) r.correct(Vec2(1.0, 0.0), k * kImuNs, Vec2::Zero());
  const Vec2 before = r.bias();
  // WHEN a sample repeats the last stamp, or is older
  const Vec2 out = r.correct(Vec2(50.0, 0.0), 500 * kImuNs, Vec2::Zero());
  r.correct(Vec2(50.0, 0.0), 3 * kImuNs, Vec2::Zero());
  // THEN the mean is unchanged and the sample is corrected with it
  EXPECT_EQ(r.bias(), before);
  EXPECT_EQ(out, Vec2(50.0, 0.0) - before);
}

}  // namespace
}  // namespace swa::agent
