// Heading dynamics (issue #26): the yaw rate follows the commanded one with a first-order lag, clamped to the
// vehicle's limit; the failsafe holds the heading; a world that never hears a yaw rate keeps its closed-form
// headings bit for bit; the field of view turns with the heading and its mounting.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "swa/sim/world.h"
#include "world_support.h"

namespace swa::sim {
namespace {

using agent::Vec2;

void commandYaw(World& world, double yaw_rate) {
  for (int i = 0; i < world.uav_count(); ++i) {
    agent::VelocityCommand cmd;
    cmd.stamp_ns = world.time_ns();
    cmd.yaw_rate_radps = yaw_rate;
    world.command(i, cmd);
  }
}

void stepFor(World& world, double seconds, double yaw_rate) {
  const std::int64_t steps = std::llround(seconds * world.scenario().dynamics.rate_hz);
  for (std::int64_t k = 0; k < steps; ++k) {
    commandYaw(world, yaw_rate);
    world.step();
  }
}

TEST(WorldHeading, YawRateReaches63PercentOfAStepCommandAfterOneLagAndTheHeadingIntegratesIt) {
  Scenario s = testing::calmScenario(1, 3);
  testing::sensorsOff(s);
  s.dynamics.yaw_lag_s = 0.5;
  World world(s);
  stepFor(world, 0.5, 0.4);
  // heading after one lag: 0.4 (t - tau (1 - e^-t/tau)) = 0.4 * 0.5 / e
  EXPECT_NEAR(world.truth()[0].heading_rad, 0.4 * 0.5 * std::exp(-1.0), 2e-3);
  stepFor(world, 5.0, 0.4);
  // then it turns at the commanded rate (wrapped to (-pi, pi])
  const double before = world.truth()[0].heading_rad;
  stepFor(world, 1.0, 0.4);
  // (the lag's residual after 11 lags, e^-11, integrates to a few micro-radians)
  EXPECT_NEAR(std::remainder(world.truth()[0].heading_rad - before, 2.0 * M_PI), 0.4, 1e-5);
}

TEST(WorldHeading, CommandsBeyondTheVehiclesLimitAreClampedAndNonFiniteOnesDropped) {
  Scenario s = testing::calmScenario(1, 3);
  testing::sensorsOff(s);
  s.dynamics.max_yaw_rate_radps = 0.25;
  World world(s);
  stepFor(world, 5.0, 100.0);
  const double before = world.truth()[0].heading_rad;
  stepFor(world, 1.0, 100.0);
  EXPECT_NEAR(std::remainder(world.truth()[0].heading_rad - before, 2.0 * M_PI), 0.25, 1e-6);
  // a NaN or infinite yaw rate drops the whole setpoint: the previous one stays in force
  const double held = world.truth()[0].heading_rad;
  commandYaw(world, std::numeric_limits<double>::quiet_NaN());
  world.step();
  commandYaw(world, -std::numeric_limits<double>::infinity());
  world.step();
  EXPECT_TRUE(std::isfinite(world.truth()[0].heading_rad));
  EXPECT_NEAR(std::remainder(world.truth()[0].heading_rad - held, 2.0 * M_PI), 2 * 0.25 * 0.01, 1e-6);
}

TEST(WorldHeading, TheFailsafeHoldsTheHeading) {
  Scenario s = testing::calmScenario(1, 3);
  testing::sensorsOff(s);
  World world(s);
  stepFor(world, 3.0, 0.5);
  // no command for 10 s: the failsafe (0.5 s) brings the yaw rate to 0 (e^-30 left after 9.5 s of 0.3 s lags),
  // then the heading stays
  for (int k = 0; k < 1000; ++k) world.step();
  const double held = world.truth()[0].heading_rad;
  for (int k = 0; k < 200; ++k) world.step();
  EXPECT_NEAR(world.truth()[0].heading_rad, held, 1e-6);
}

TEST(WorldHeading, AWorldThatOnlyHearsZeroYawRatesKeepsItsClosedFormHeadingsBitForBit) {
  Scenario s = testing::calmScenario(3, 5);
  s.dynamics.heading = HeadingMode::kRandom;
  s.dynamics.heading_rate_std_radps = 0.1;
  World commanded(s);
  World silent(s);
  for (int k = 0; k < 1000; ++k) {
    commandYaw(commanded, 0.0);
    commanded.step();
    silent.step();
  }
  for (int i = 0; i < 3; ++i) EXPECT_EQ(commanded.truth()[i].heading_rad, silent.truth()[i].heading_rad);
}

TEST(WorldHeading, TheFieldOfViewIsCentredOnItsMounting) {
  // GIVEN two UAVs east-west of each other, both heading east, a 90 deg sensor mounted facing left (+90 deg)
  Scenario s = testing::calmScenario(2, 3);
  s.mps.fov_deg = 90.0;
  s.mps.mount_deg = 90.0;
  s.mps.miss_probability = 0.0;
  World world(s);
  // THEN neither sees the other (each is at 0 or 180 deg, outside 45..135)
  for (int k = 0; k < 10 && !world.sensors()[0].detections; ++k) world.step();
  ASSERT_TRUE(world.sensors()[0].detections.has_value());
  EXPECT_TRUE(world.sensors()[0].detections->detections.empty());
  // AND mounted facing forward, exactly one of them sees the other (the one facing it)
  s.mps.mount_deg = 0.0;
  World turned(s);
  for (int k = 0; k < 10 && !turned.sensors()[0].detections; ++k) turned.step();
  const std::size_t seen =
      turned.sensors()[0].detections->detections.size() + turned.sensors()[1].detections->detections.size();
  EXPECT_EQ(seen, 1u);
}

}  // namespace
}  // namespace swa::sim
