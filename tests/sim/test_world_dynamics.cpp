// Lateral dynamics: velocity lag, speed limit, failsafe, wind gusts.
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "swa/sim/world.h"
#include "world_support.h"

namespace swa::sim {
namespace {

using agent::Vec2;

// No wind, no sensor noise, zero headings, GNSS never lost: only what a test turns on happens.
Scenario quietScenario(int n) { return testing::calmScenario(n, 11); }

void commandAll(World& world, const Vec2& velocity) {
  for (int i = 0; i < world.uav_count(); ++i) {
    agent::VelocityCommand cmd;
    cmd.stamp_ns = world.time_ns();
    cmd.velocity_mps = velocity;
    world.command(i, cmd);
  }
}

void stepFor(World& world, double seconds, const Vec2& velocity) {
  const std::int64_t steps = std::llround(seconds * world.scenario().dynamics.rate_hz);
  for (std::int64_t k = 0; k < steps; ++k) {
    commandAll(world, velocity);
    world.step();
  }
}

int countEvents(const std::vector<Event>& events, EventKind kind) {
  int n = 0;
  for (const Event& e : events) n += e.kind == kind;
  return n;
}

TEST(WorldDynamics, ClockStartsAtZeroAndAdvancesInWholeNanosecondSteps) {
  World world(quietScenario(1));
  EXPECT_EQ(world.time_ns(), 0);
  EXPECT_EQ(world.step_index(), 0);
  for (int k = 0; k < 250; ++k) world.step();
  EXPECT_EQ(world.step_index(), 250);
  EXPECT_EQ(world.time_ns(), 2'500'000'000LL);
}

TEST(WorldDynamics, FinishesAtTheScenarioDuration) {
  Scenario s = quietScenario(1);
  s.duration_s = 0.5;
  World world(s);
  int steps = 0;
  while (!world.finished()) {
    world.step();
    ++steps;
  }
  EXPECT_EQ(steps, 50);
}

TEST(WorldDynamics, VelocityReaches63PercentOfAStepCommandAfterOneLag) {
  // GIVEN a UAV at rest, lag 1 s, no wind
  World world(quietScenario(1));
  // WHEN commanded 1 m/s east for 1 s
  stepFor(world, 1.0, Vec2(1.0, 0.0));
  // THEN its velocity is 1 - e^-1 of the command (explicit Euler at 100 Hz: 1 - 0.99^100 = 0.6340)
  const UavTruth& t = world.truth()[0];
  EXPECT_NEAR(t.velocity_mps.x(), 1.0 - std::exp(-1.0), 0.002);
  EXPECT_EQ(t.velocity_mps.y(), 0.0);
  // AND the reported acceleration is the lag's (1 - v) / tau
  EXPECT_NEAR(t.acceleration_mps2.x(), 1.0 - t.velocity_mps.x(), 0.01);
  // AND position is the integral of velocity: t - tau (1 - e^-t/tau) = 0.368 m
  EXPECT_NEAR(t.position_m.x(), std::exp(-1.0), 0.005);
  // AND after 5 lags the command is reached
  stepFor(world, 4.0, Vec2(1.0, 0.0));
  EXPECT_NEAR(world.truth()[0].velocity_mps.x(), 1.0, 0.01);
}

TEST(WorldDynamics, SpeedLimitHolds) {
  // GIVEN a 3 m/s speed limit
  Scenario s = quietScenario(1);
  s.dynamics.speed_limit_mps = 3.0;
  World world(s);
  // WHEN commanded 10 m/s diagonally for 20 s
  double max_speed = 0.0;
  for (int k = 0; k < 2000; ++k) {
    commandAll(world, Vec2(10.0, 10.0) / std::sqrt(2.0));
    world.step();
    max_speed = std::max(max_speed, world.truth()[0].velocity_mps.norm());
  }
  // THEN the speed never exceeds the limit and sits on it
  EXPECT_LE(max_speed, 3.0 + 1e-12);
  EXPECT_NEAR(world.truth()[0].velocity_mps.norm(), 3.0, 1e-9);
  // AND the acceleration reported is the achieved one (zero on the limit), not the commanded push
  EXPECT_NEAR(world.truth()[0].acceleration_mps2.norm(), 0.0, 1e-9);
}

TEST(WorldDynamics, FailsafeBrakesToHoverAfterTheTimeoutAndRecovers) {
  // GIVEN two UAVs flying east at 1 m/s for 5 s; timeout 0.5 s
  World world(quietScenario(2));
  stepFor(world, 5.0, Vec2(1.0, 0.0));
  ASSERT_NEAR(world.truth()[0].velocity_mps.x(), 0.993, 0.002);
  // WHEN UAV 0's agent goes silent (UAV 1's keeps sending the same setpoint)
  std::vector<Event> seen;
  for (int k = 0; k < 550; ++k) {
    agent::VelocityCommand cmd;
    cmd.velocity_mps = Vec2(1.0, 0.0);
    world.command(1, cmd);
    world.step();
    seen.insert(seen.end(), world.events().begin(), world.events().end());
  }
  // THEN UAV 0 enters failsafe once, at the first step starting more than 0.5 s after its last setpoint (4.99 s)
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].kind, EventKind::kFailsafeOn);
  EXPECT_EQ(seen[0].uav, 0);
  EXPECT_EQ(seen[0].stamp_ns, 5'500'000'000LL);
  EXPECT_NEAR(seen[0].value, 0.51, 1e-9);
  // AND after 5 more seconds it hovers (1 m/s decays by e^-5) while UAV 1 still flies
  EXPECT_TRUE(world.truth()[0].failsafe);
  EXPECT_FALSE(world.truth()[1].failsafe);
  EXPECT_LT(world.truth()[0].velocity_mps.norm(), 0.01);
  EXPECT_NEAR(world.truth()[1].velocity_mps.x(), 1.0, 1e-3);
  // WHEN UAV 0's agent comes back
  commandAll(world, Vec2(0.5, 0.0));
  world.step();
  // THEN failsafe ends at once, with one event
  ASSERT_EQ(world.events().size(), 1u);
  EXPECT_EQ(world.events()[0].kind, EventKind::kFailsafeOff);
  EXPECT_EQ(world.events()[0].stamp_ns, 10'500'000'000LL);
  EXPECT_FALSE(world.truth()[0].failsafe);
  stepFor(world, 1.0, Vec2(0.5, 0.0));
  EXPECT_EQ(countEvents(world.events(), EventKind::kFailsafeOn), 0);
  EXPECT_GT(world.truth()[0].velocity_mps.x(), 0.3);
}

TEST(WorldDynamics, UavThatNeverHeardFromItsAgentEntersFailsafeAfterTheFirstTimeout) {
  World world(quietScenario(1));
  int on_events = 0;
  agent::StampNs on_stamp = -1;
  for (int k = 0; k < 100; ++k) {
    world.step();
    for (const Event& e : world.events()) {
      if (e.kind == EventKind::kFailsafeOn) {
        ++on_events;
        on_stamp = e.stamp_ns;
      }
    }
  }
  EXPECT_EQ(on_events, 1);
  EXPECT_EQ(on_stamp, 510'000'000LL);
  EXPECT_TRUE(world.truth()[0].failsafe);
}

TEST(WorldDynamics, NonFiniteSetpointIsDroppedAndUnknownUavRejected) {
  World world(quietScenario(2));
  stepFor(world, 1.0, Vec2(1.0, 0.0));
  agent::VelocityCommand bad;
  bad.velocity_mps = Vec2(std::numeric_limits<double>::quiet_NaN(), 0.0);
  world.command(0, bad);
  world.step();
  EXPECT_TRUE(agent::isFinite(world.truth()[0].velocity_mps));
  EXPECT_GT(world.truth()[0].velocity_mps.x(), 0.6);  // the previous setpoint stays in force
  EXPECT_THROW(world.command(2, bad), std::out_of_range);
  EXPECT_THROW(world.command(-1, bad), std::out_of_range);
}

TEST(WorldWind, PerUavGustHasTheConfiguredStdAndCorrelationTime) {
  // GIVEN 8 hovering UAVs in 0.2 m/s^2, 5 s gusts, sensors off (not needed here)
  Scenario s = quietScenario(8);
  s.wind.gust_std = 0.2;
  s.wind.gust_corr_s = 5.0;
  testing::sensorsOff(s);
  World world(s);
  // WHEN run for 1000 s, sampling the gust every 0.1 s
  constexpr int kSamples = 10000;
  constexpr int kLag = 50;  // 5 s
  std::vector<std::vector<double>> series(16, std::vector<double>(kSamples));
  for (int k = 0; k < kSamples; ++k) {
    stepFor(world, 0.1, Vec2::Zero());
    for (std::size_t i = 0; i < 8; ++i) {
      series[2 * i][static_cast<std::size_t>(k)] = world.truth()[i].gust_mps2.x();
      series[2 * i + 1][static_cast<std::size_t>(k)] = world.truth()[i].gust_mps2.y();
    }
  }
  double sum2 = 0.0, lagged = 0.0, lagged_norm = 0.0;
  for (const std::vector<double>& x : series) {
    for (std::size_t k = 0; k < x.size(); ++k) {
      sum2 += x[k] * x[k];
      if (k + kLag < x.size()) {
        lagged += x[k] * x[k + kLag];
        lagged_norm += x[k] * x[k];
      }
    }
  }
  const double std_measured = std::sqrt(sum2 / (16.0 * kSamples));
  std::printf("per-UAV gust: std %.4f m/s^2, autocorrelation at 5 s %.3f\n", std_measured, lagged / lagged_norm);
  // THEN the stationary std is 0.2 (+-10 %; 16 series of 200 correlation times: ~1.3 % expected error)
  EXPECT_NEAR(std_measured, 0.2, 0.02);
  // AND the autocorrelation one correlation time apart is e^-1
  EXPECT_NEAR(lagged / lagged_norm, std::exp(-1.0), 0.05);
  // AND the hovering UAVs' velocity responds to it (lagged gust: std ~ sigma sqrt(tau corr/(tau+corr)) ~ 0.18 m/s)
  double v2 = 0.0;
  for (const UavTruth& t : world.truth()) v2 += t.velocity_mps.squaredNorm() / 16.0;
  EXPECT_GT(std::sqrt(v2), 0.02);
}

TEST(WorldWind, CommonGustIsTheSameForEveryUavAndHasItsStd) {
  // GIVEN no per-UAV gust and a common 0.3 m/s^2 gust with 2 s correlation
  Scenario s = quietScenario(4);
  s.wind.common_std = 0.3;
  s.wind.common_corr_s = 2.0;
  testing::sensorsOff(s);
  World world(s);
  double sum2 = 0.0;
  int n = 0;
  for (int k = 0; k < 100000; ++k) {
    commandAll(world, Vec2::Zero());
    world.step();
    const std::vector<UavTruth>& truth = world.truth();
    // THEN every UAV feels exactly the same gust and, starting alike, moves exactly alike
    for (std::size_t i = 1; i < truth.size(); ++i) {
      ASSERT_EQ(truth[i].gust_mps2, truth[0].gust_mps2);
      ASSERT_EQ(truth[i].velocity_mps, truth[0].velocity_mps);
    }
    if (k % 10 == 0) {
      sum2 += truth[0].gust_mps2.squaredNorm();
      n += 2;
    }
  }
  std::printf("common gust: std %.4f m/s^2\n", std::sqrt(sum2 / n));
  // AND its std over 1000 s is 0.3 (+-10 %; ~2 % expected error)
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.3, 0.03);
}

}  // namespace
}  // namespace swa::sim
