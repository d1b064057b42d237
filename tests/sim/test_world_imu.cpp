// IMU: tilt generated from the true acceleration in the agent's convention, with bias and noise of the set size.
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "swa/sim/imu_model.h"
#include "swa/sim/timing.h"
#include "swa/sim/world.h"

namespace swa::sim {
namespace {

using agent::Vec2;

// The agent's reading of a tilt sample (DESIGN §3.4, agent.cpp): a_S = q_c R(psi) [pitch, roll].
Vec2 derivedAcceleration(const agent::ImuSample& imu, double q_c) {
  return q_c * (agent::rotation(imu.heading_rad) * Vec2(imu.pitch_rad, imu.roll_rad));
}

ImuModel::Streams streams(std::uint64_t seed = 1) { return ImuModel::Streams::of(seed, 0); }

Scenario windyHover(int n) {
  Scenario s;
  s.uav_count = n;
  s.seed = 5;
  s.formation.position_jitter_m = 0.0;
  s.dynamics.failsafe_timeout_s = std::numeric_limits<double>::infinity();  // hover on the zero setpoint
  s.gnss.dropout_start_s = std::numeric_limits<double>::infinity();
  s.mps.rate_hz = 0.0;
  return s;
}

TEST(WorldImu, TiltRoundTripThroughTheAgentConventionRecoversAccelerationPlusBias) {
  // GIVEN a noise-free IMU with a body-fixed bias, q_c = 6.35
  ImuSetup setup;
  setup.noise_std = 0.0;
  setup.heading_noise_std_rad = 0.0;
  setup.bias_std = 0.05;
  ImuModel imu(setup, 6.35, streams());
  ASSERT_GT(imu.bias_body_mps2().norm(), 0.0);
  for (const double heading : {0.0, 0.7, M_PI / 2, -2.5, M_PI}) {
    // WHEN the UAV accelerates at (0.8, -0.3) m/s^2 in the world with that heading
    const Vec2 a(0.8, -0.3);
    const agent::ImuSample sample = imu.sample(123, a, a, heading);
    // THEN the agent's convention gives back the acceleration plus the bias turned into the world frame
    const Vec2 expected = a + agent::rotation(heading) * imu.bias_body_mps2();
    EXPECT_NEAR(derivedAcceleration(sample, 6.35).x(), expected.x(), 1e-12) << heading;
    EXPECT_NEAR(derivedAcceleration(sample, 6.35).y(), expected.y(), 1e-12) << heading;
    EXPECT_EQ(sample.stamp_ns, 123);
    EXPECT_NEAR(std::remainder(sample.heading_rad - heading, 2 * M_PI), 0.0, 1e-12);
  }
  // AND pitch is body-x, roll body-y: heading east, accelerating north is a positive roll only
  setup.bias_std = 0.0;
  const agent::ImuSample north = ImuModel(setup, 6.35, streams()).sample(0, Vec2(0, 0.635), Vec2(0, 0.635), 0.0);
  EXPECT_NEAR(north.roll_rad, 0.1, 1e-15);
  EXPECT_NEAR(north.pitch_rad, 0.0, 1e-15);
}

TEST(WorldImu, DerivedAccelerationNoiseHasTheConfiguredVarianceAroundTruth) {
  // GIVEN a UAV hovering in gusts with an unbiased IMU (noise 1.5 m/s^2, heading noise 5 mrad), random heading
  Scenario s = windyHover(1);
  s.imu.bias_std = 0.0;
  World world(s);
  const double q_c = s.agent.focal.q_c_mps2;
  // WHEN 200 s of IMU samples are compared with the true acceleration
  Vec2 sum = Vec2::Zero();
  Vec2 sum2 = Vec2::Zero();
  double heading_err2 = 0.0;
  int n = 0;
  for (int k = 0; k < 20000; ++k) {
    world.step();
    const auto& imu = world.sensors()[0].imu;
    ASSERT_TRUE(imu.has_value());  // every step at 100 Hz
    ASSERT_EQ(imu->stamp_ns, world.time_ns());
    const Vec2 err = derivedAcceleration(*imu, q_c) - world.truth()[0].thrust_mps2;
    sum += err;
    sum2 += err.cwiseProduct(err);
    heading_err2 += std::pow(std::remainder(imu->heading_rad - world.truth()[0].heading_rad, 2 * M_PI), 2);
    ++n;
  }
  const Vec2 mean = sum / n;
  const Vec2 var = sum2 / n - mean.cwiseProduct(mean);
  std::printf("derived acceleration error: mean (%.4f, %.4f), variance (%.3f, %.3f) m^2/s^4, heading std %.5f rad\n",
              mean.x(), mean.y(), var.x(), var.y(), std::sqrt(heading_err2 / n));
  // THEN it is unbiased (4 sigma of the mean: 4 * 1.5 / sqrt(20000) = 0.042)
  EXPECT_LT(mean.cwiseAbs().maxCoeff(), 0.042);
  // AND its variance per axis is noise_std^2 = 2.25 = R_a (+-10 %)
  EXPECT_NEAR(var.x(), 2.25, 0.225);
  EXPECT_NEAR(var.y(), 2.25, 0.225);
  // AND the heading noise std is 5 mrad (+-10 %)
  EXPECT_NEAR(std::sqrt(heading_err2 / n), 0.005, 0.0005);
}

TEST(WorldImu, BiasIsConstantPerUavWithTheConfiguredSpread) {
  // GIVEN 200 noise-free IMUs with bias std 0.05 m/s^2
  Scenario s = windyHover(200);
  s.imu.noise_std = 0.0;
  s.imu.heading_noise_std_rad = 0.0;
  s.imu.bias_std = 0.05;
  World world(s);
  const double q_c = s.agent.focal.q_c_mps2;
  std::vector<Vec2> first(200);
  double sum2 = 0.0;
  for (int k = 0; k < 50; ++k) {
    world.step();
    for (std::size_t i = 0; i < 200; ++i) {
      const Vec2 bias_world = derivedAcceleration(*world.sensors()[i].imu, q_c) - world.truth()[i].thrust_mps2;
      // THEN the bias seen in the body frame does not change over time
      const Vec2 bias_body = agent::rotation(-world.truth()[i].heading_rad) * bias_world;
      if (k == 0) {
        first[i] = bias_body;
        sum2 += bias_body.squaredNorm();
      } else {
        EXPECT_NEAR((bias_body - first[i]).norm(), 0.0, 1e-12);
      }
    }
  }
  const double std_measured = std::sqrt(sum2 / 400.0);
  std::printf("IMU bias std over 200 UAVs: %.4f m/s^2\n", std_measured);
  // AND its spread across UAVs is 0.05 per axis (+-15 %; 400 draws give ~3.5 %)
  EXPECT_NEAR(std_measured, 0.05, 0.0075);
}

TEST(WorldImu, ImuAtHalfTheDynamicsRateSamplesEveryOtherStep) {
  Scenario s = windyHover(1);
  s.imu.rate_hz = 50.0;
  World world(s);
  ASSERT_TRUE(world.sensors()[0].imu.has_value());
  int samples = 0;
  for (int k = 1; k <= 100; ++k) {
    world.step();
    if (world.sensors()[0].imu) {
      ++samples;
      EXPECT_EQ(world.sensors()[0].imu->stamp_ns, static_cast<agent::StampNs>(k) * 10'000'000LL);
      EXPECT_EQ(k % 2, 0);
    }
  }
  EXPECT_EQ(samples, 50);
}

// The compass's bias (issue #44): constant per UAV with the configured spread, and a random walk whose change over t
// has std walk x sqrt(t).
TEST(WorldImu, TheCompassBiasIsConstantPerUavWithTheConfiguredSpread) {
  // GIVEN 400 noise-free IMUs with heading bias std 0.087 rad (5 deg)
  Scenario s = windyHover(400);
  s.imu.noise_std = 0.0;
  s.imu.heading_noise_std_rad = 0.0;
  s.imu.heading_bias_std_rad = 0.087;
  World world(s);
  std::vector<double> first(400);
  double sum = 0.0, sum2 = 0.0;
  for (int k = 0; k < 20; ++k) {
    world.step();
    for (std::size_t i = 0; i < 400; ++i) {
      const double bias = std::remainder(world.sensors()[i].imu->heading_rad - world.truth()[i].heading_rad, 2 * M_PI);
      // THEN each UAV's heading is off by the same angle at every sample
      if (k == 0) {
        first[i] = bias;
        sum += bias;
        sum2 += bias * bias;
      } else {
        ASSERT_NEAR(bias, first[i], 1e-12) << "UAV " << i;
      }
    }
  }
  // AND across UAVs the offsets are centred on 0 with std 0.087 (+-10 %; 4 sigma of the mean: 0.017)
  EXPECT_LT(std::abs(sum / 400.0), 0.017);
  EXPECT_NEAR(std::sqrt(sum2 / 400.0), 0.087, 0.0087);
}

TEST(WorldImu, TheCompassBiasWalksWithStdGrowingAsTheSquareRootOfTime) {
  // GIVEN 200 noise-free IMUs whose compass bias walks at 0.002 rad/sqrt(s), from 0
  Scenario s = windyHover(200);
  s.imu.noise_std = 0.0;
  s.imu.heading_noise_std_rad = 0.0;
  s.imu.heading_bias_walk_radps = 0.002;
  World world(s);
  // WHEN 100 s go by (10 000 IMU samples)
  for (int k = 0; k < 10000; ++k) world.step();
  double sum2 = 0.0;
  for (std::size_t i = 0; i < 200; ++i) {
    sum2 += std::pow(std::remainder(world.sensors()[i].imu->heading_rad - world.truth()[i].heading_rad, 2 * M_PI), 2);
  }
  // THEN the biases' spread is 0.002 x sqrt(100) = 0.02 rad (+-15 % for 200 draws: 3 sigma of a std estimate is 15 %)
  EXPECT_NEAR(std::sqrt(sum2 / 200.0), 0.02, 0.003);
}

TEST(WorldImu, TheCompassBiasTurnsTheHeadingAndNothingElse) {
  // GIVEN the default world and the same with a biased compass
  Scenario a = windyHover(3);
  Scenario c = a;
  c.imu.heading_bias_std_rad = 0.05;
  World wa(a), wc(c);
  for (int k = 0; k < 300; ++k) {
    wa.step();
    wc.step();
    for (std::size_t i = 0; i < 3; ++i) {
      const agent::ImuSample &ia = *wa.sensors()[i].imu, &ic = *wc.sensors()[i].imu;
      // THEN the tilt is the same bits (the bias has its own draw, after the acceleration bias's), the heading not
      ASSERT_EQ(ia.pitch_rad, ic.pitch_rad);
      ASSERT_EQ(ia.roll_rad, ic.roll_rad);
      ASSERT_NE(ia.heading_rad, ic.heading_rad);
    }
  }
}

}  // namespace
}  // namespace swa::sim
