// Issue #11 at the Agent facade: one far-future stamp does not ground the agent, a producer whose clock restarts is
// followed after a few samples (and the estimates restart), a flood of stale samples produces no fresh command, and
// the smaller limits (heading, saturation rounding) hold. The closed loop is the tiny FocalWorld of
// focal_scenario.h: three hovering neighbours, the UAV starting 4 m from its frame origin.

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "focal_scenario.h"
#include "swa/agent/agent.h"
#include "swa/agent/controller.h"

namespace swa::agent {
namespace {

AgentConfig tiltOnly() {
  AgentConfig c;
  c.focal.imu_source = ImuSource::kTilt;
  return c;
}

using testing::FocalWorld;

constexpr StampNs kStepNs = 10'000'000;  // 100 Hz

std::vector<Vec2> ring() {
  std::vector<Vec2> out;
  for (double deg : {90.0, 210.0, 330.0})
    out.push_back(10.0 * Vec2(std::cos(deg * M_PI / 180), std::sin(deg * M_PI / 180)));
  return out;
}

// One agent flying in a FocalWorld; `offset_ns` is added to every stamp the world produces (a producer's clock).
struct Flight {
  Flight() : agent(AgentConfig{}), world(3, ring(), Vec2(4.0, 0.0), FocalWorld::Options{}) {}

  // `steps` 10 ms steps; returns how many commands were fresh.
  int run(int steps) {
    int fresh = 0;
    for (int i = 0; i < steps; ++i, ++k) {
      const StampNs t = k * kStepNs + offset_ns;
      world.step(0.01, u);
      const VelocityCommand c = agent.onImu(world.imu(t));
      if (c.fresh) {
        u = c.velocity_mps;
        ++fresh;
      }
      if (k % 10 == 0) agent.onDetections(world.detections(t));
    }
    return fresh;
  }
  double distanceToOrigin() const { return world.p.norm(); }

  Agent agent;
  FocalWorld world;
  Vec2 u = Vec2::Zero();
  StampNs k = 0;
  StampNs offset_ns = 5'000'000'000;
};

TEST(AgentStamps, OneImuSampleSixtySecondsAheadDoesNotGroundTheAgent) {
  // GIVEN an agent flying to its frame origin for 10 s
  Flight f;
  f.run(1000);
  ASSERT_EQ(f.agent.diagnostics().stage, Stage::kTracking);
  // WHEN one IMU sample stamped 60 s ahead arrives, then one stamped INT64_MAX
  ImuSample rogue = f.world.imu(f.k * kStepNs + f.offset_ns + 60'000'000'000);
  EXPECT_FALSE(f.agent.onImu(rogue).fresh);
  rogue.stamp_ns = std::numeric_limits<StampNs>::max();
  EXPECT_FALSE(f.agent.onImu(rogue).fresh);
  // THEN both are counted as future stamps and every following genuine sample is answered fresh (before issue #11
  // the agent accepted the first and hovered for the next 60 s)
  EXPECT_EQ(f.agent.diagnostics().rejected.future, 2u);
  EXPECT_EQ(f.run(1000), 1000);
  EXPECT_EQ(f.agent.diagnostics().stage, Stage::kTracking);
  EXPECT_LT(f.distanceToOrigin(), 1.5);
  EXPECT_EQ(f.agent.diagnostics().stamp_resyncs, 0u);
}

TEST(AgentStamps, ProducerClockRestartIsFollowedWithinFourSamples) {
  // GIVEN an agent tracking for 20 s on a producer clock that started at 5 s
  Flight f;
  f.run(2000);
  ASSERT_EQ(f.agent.diagnostics().stage, Stage::kTracking);
  // WHEN the producer reboots: its stamps restart near 0 (all streams)
  f.offset_ns = -f.k * kStepNs;
  const int fresh = f.run(1000);
  // THEN the first resync_samples - 1 IMU samples (3) are rejected, the next re-synchronises (counted), every later
  // one is fresh, and the agent tracks again in the new timeline (before: zero setpoints for as long as the old
  // stamps were ahead). The detection set of the first restarted step is rejected too; after the resync the
  // detections start afresh.
  const int lost = f.agent.config().limits.resync_samples - 1;
  EXPECT_EQ(lost, 3);
  EXPECT_EQ(fresh, 1000 - lost);
  EXPECT_EQ(f.agent.diagnostics().stamp_resyncs, 1u);
  EXPECT_EQ(f.agent.diagnostics().rejected.out_of_order, static_cast<std::uint64_t>(lost + 1));
  EXPECT_EQ(f.agent.diagnostics().stage, Stage::kTracking);
  EXPECT_LT(f.agent.diagnostics().stamp_ns, 20'000'000'000);  // the diagnostics follow the new timeline
  EXPECT_LT(f.distanceToOrigin(), 1.5);
}

TEST(AgentStamps, FloodOfStaleSamplesGivesNoFreshCommandAndDoesNotHover) {
  // GIVEN an agent flying towards the group from 25 m away, its last command saturated
  Flight f;
  f.world.p = Vec2(25.0, 0.0);
  f.run(150);
  const VelocityCommand before = f.agent.onImu(f.world.imu(f.k * kStepNs + f.offset_ns));
  ++f.k;
  ASSERT_TRUE(before.fresh);
  ASSERT_GT(before.velocity_mps.norm(), 0.5);
  // WHEN 10000 stale samples (old random stamps) arrive between two genuine ones
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<StampNs> old(0, f.offset_ns);
  int fresh = 0;
  for (int i = 0; i < 10000; ++i) {
    ImuSample s = f.world.imu(old(rng));
    const VelocityCommand c = f.agent.onImu(s);
    fresh += c.fresh ? 1 : 0;
    // THEN none is fresh, and each is answered with the last command, not with hover (a flood must not ground it)
    ASSERT_EQ(c.velocity_mps, before.velocity_mps);
  }
  EXPECT_EQ(fresh, 0);
  EXPECT_EQ(f.agent.diagnostics().rejected.out_of_order, 10000u);
  EXPECT_EQ(f.agent.diagnostics().stamp_resyncs, 0u);
  // AND the genuine stream goes on
  EXPECT_EQ(f.run(100), 100);
}

TEST(AgentStamps, DetectionsOffTheImuClockAreRejected) {
  Flight f;
  f.run(500);
  const StampNs now = f.k * kStepNs + f.offset_ns;
  const std::uint64_t before = f.agent.diagnostics().rejected.total();
  // Detections 30 s ahead of the IMU clock (their own stream would take them after 3 consistent sets)
  for (int i = 0; i < 5; ++i) f.agent.onDetections(f.world.detections(now + 30'000'000'000 + i * 100'000'000));
  EXPECT_EQ(f.agent.diagnostics().rejected.future, 5u);
  EXPECT_EQ(f.agent.diagnostics().rejected.total(), before + 5);
  EXPECT_EQ(f.run(500), 500);
}

TEST(AgentLimits, HeadingBeyondFourPiIsImplausible) {
  Agent agent{tiltOnly()};  // tilt-only samples below
  ImuSample s;
  s.stamp_ns = 1;
  s.heading_rad = 1e300;  // before issue #11: accepted
  EXPECT_FALSE(agent.onImu(s).fresh);
  s.stamp_ns = 2;
  s.heading_rad = -13.0;
  EXPECT_FALSE(agent.onImu(s).fresh);
  EXPECT_EQ(agent.diagnostics().rejected.implausible, 2u);
  s.stamp_ns = 3;
  s.heading_rad = 12.5;  // two turns minus a little: an unwrapped heading is fine
  EXPECT_TRUE(agent.onImu(s).fresh);
}

TEST(AgentLimits, SaturatedCommandIsNeverARoundingStepOverTheLimit) {
  // GIVEN 1e6 seeded directions and magnitudes above v_max (before issue #11, 265 of a run's commands had
  // |v| = 2.0000000000000004)
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI), scale(1.0, 1e6);
  int over = 0, shortened = 0;
  for (int i = 0; i < 1'000'000; ++i) {
    const double v_max = i % 2 == 0 ? 2.0 : 0.7;
    const Vec2 v = scale(rng) * v_max * Vec2(std::cos(angle(rng)), std::sin(angle(rng)));
    const Vec2 s = saturate(v, v_max);
    over += s.norm() > v_max ? 1 : 0;
    shortened += s.norm() < v_max * (1.0 - 1e-12) ? 1 : 0;
  }
  // THEN none is above the limit, and none is noticeably below it
  EXPECT_EQ(over, 0);
  EXPECT_EQ(shortened, 0);
}

TEST(AgentLimits, IdsAboveTheSwarmsLargestAreCorrupt) {
  // GIVEN the default limit (255: the simulator's largest UAV id) and detections of ids 255, 256 and 1,000,000
  Agent agent{tiltOnly()};  // tilt-only samples below
  ImuSample s;
  s.stamp_ns = 1;
  agent.onImu(s);
  DetectionSet set;
  set.stamp_ns = 2;
  set.detections = {
      {255, Vec2(5, 0), std::nullopt}, {256, Vec2(0, 5), std::nullopt}, {1'000'000, Vec2(5, 5), std::nullopt}};
  agent.onDetections(set);
  // THEN only 255 starts a track: before issue #11 ids up to 1,000,000 made phantom neighbours
  EXPECT_EQ(agent.diagnostics().rejected.bad_id, 2u);
  EXPECT_NE(agent.bank().find(255), nullptr);
  EXPECT_EQ(agent.bank().find(1'000'000), nullptr);
}

}  // namespace
}  // namespace swa::agent
