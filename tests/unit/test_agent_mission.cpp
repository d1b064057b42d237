// The agent flying a mission (issue #45): the plan's velocity as a feed-forward under the formation law, the focal
// filter in a frame that moves with the plan, the start at GNSS loss or at a time, the heading along the direction of
// travel, a standalone UAV following the plan on its own dead reckoning, and a hold when the plan's clock is lost.

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "focal_scenario.h"
#include "swa/agent/agent.h"

namespace swa::agent {
namespace {

using testing::FocalWorld;

constexpr StampNs kStep = 10'000'000;  // 10 ms

AgentConfig withPlan(std::vector<MissionLeg> legs, MissionStart start = MissionStart::kTime, double start_s = 0.0) {
  AgentConfig c;
  c.mission.legs = std::move(legs);
  c.mission.start = start;
  c.mission.start_s = start_s;
  return c;
}

std::vector<Vec2> triangleAround(const Vec2& centre) {
  std::vector<Vec2> out;
  for (double d : {90.0, 210.0, 330.0}) {
    out.push_back(centre + 10.0 * Vec2(std::cos(d * M_PI / 180), std::sin(d * M_PI / 180)));
  }
  return out;
}

// One agent among neighbours that fly the plan exactly (the rest of the swarm), closed loop, 10 ms steps.
struct MovingSwarm {
  MovingSwarm(const AgentConfig& cfg, std::uint64_t seed)
      : agent(cfg),
        plan(cfg.mission.legs),
        start_s(cfg.mission.start_s),
        world(seed, triangleAround(Vec2::Zero()), Vec2(0.5, -0.5), {}) {}
  void run(int steps) {
    for (int i = 0; i < steps; ++i, ++k) {
      const StampNs t = static_cast<StampNs>(k) * kStep;
      const Vec2 v = plan.velocityAt(static_cast<double>(t) * 1e-9 - start_s);
      for (Vec2& n : world.neighbours) n += v * 0.01;
      world.step(0.01, u);
      if (k % 10 == 0) agent.onDetections(world.detections(t));
      u = agent.onImu(world.imu(t)).velocity_mps;
    }
  }
  Vec2 swarmCentre() const { return (world.neighbours[0] + world.neighbours[1] + world.neighbours[2]) / 3.0; }
  Agent agent;
  MissionPlan plan;
  double start_s;
  FocalWorld world;
  Vec2 u = Vec2::Zero();
  long k = 0;
};

TEST(AgentMission, AnAgentWithoutNeighboursFliesThePlanThenHolds) {
  // GIVEN an agent with a plan of 5 s at (2, 1) m/s from 0 s, and nobody to see
  Agent agent(withPlan({{Vec2(2, 1), 5.0}}));
  FocalWorld world(3, {}, Vec2::Zero(), {});
  // WHEN it runs through the leg and past it
  for (int k = 0; k < 700; ++k) {
    const VelocityCommand cmd = agent.onImu(world.imu(static_cast<StampNs>(k) * kStep));
    // THEN it commands the plan's velocity during the leg (the lost agent flies where its swarm goes) and a hover
    // after it, exactly: the formation's correction is zero without a frame
    const Vec2 expected = k < 500 ? Vec2(2, 1) : Vec2::Zero();
    ASSERT_EQ(cmd.velocity_mps, expected) << "step " << k;
  }
  EXPECT_EQ(agent.diagnostics().mission_leg, 1);  // the hold after the only leg
  EXPECT_EQ(agent.diagnostics().plan_velocity_mps, Vec2::Zero());
}

TEST(AgentMission, InASwarmThatFliesThePlanTheAgentKeepsItsSlotAndItsFrameMovesWithThePlan) {
  // GIVEN an agent settled among three neighbours, then a plan of 30 s north-east at 3 m/s that they fly too
  const Vec2 velocity = 3.0 * Vec2(1, 1).normalized();
  MovingSwarm swarm(withPlan({{velocity, 30.0}}, MissionStart::kTime, 20.0), 7);
  swarm.run(2000);
  const Vec2 slot_before = swarm.world.p - swarm.swarmCentre();
  // WHEN the plan has run for 25 s
  swarm.run(2500);
  // THEN the UAV moves with the swarm at the plan's velocity and holds its place in it
  EXPECT_LT((swarm.world.v - velocity).norm(), 0.5);
  EXPECT_LT(((swarm.world.p - swarm.swarmCentre()) - slot_before).norm(), 1.0);
  // AND its focal velocity is taken in the plan's frame: near zero, not the 3 m/s it flies
  EXPECT_LT(swarm.agent.focal().velocity().norm(), 0.5);
  EXPECT_EQ(swarm.agent.diagnostics().plan_velocity_mps, velocity);
  EXPECT_EQ(swarm.agent.diagnostics().mission_leg, 0);
}

TEST(AgentMission, TheNextLegShiftsTheFocalVelocityByTheChangeOfThePlan) {
  // GIVEN an agent in a swarm flying east at 2 m/s, whose plan turns to north at 2 m/s at 30 s
  MovingSwarm swarm(withPlan({{Vec2(2, 0), 30.0}, {Vec2(0, 2), 30.0}}), 11);
  swarm.run(3000);  // the IMU steps of the first leg: 0 ... 29.99 s
  const Vec2 before = swarm.agent.focal().velocity();
  // WHEN the IMU step at 30 s begins the second leg
  swarm.run(1);
  // THEN the focal velocity, the UAV's relative to the plan, jumps by minus the change: the UAV itself still flies
  // east (the filter's own prediction and correction of that one step move it by far less than 0.5 m/s)
  EXPECT_NEAR((swarm.agent.focal().velocity() - before - Vec2(2, -2)).norm(), 0.0, 0.5);
  EXPECT_EQ(swarm.agent.diagnostics().plan_velocity_mps, Vec2(0, 2));
}

TEST(AgentMission, AMissionStartedAtGnssLossBeginsAtTheFirstSampleWithoutAFix) {
  // GIVEN an agent with a plan that starts at GNSS loss, and valid fixes up to 3 s
  Agent agent(withPlan({{Vec2(1, 0), 10.0}}, MissionStart::kGnssLoss));
  FocalWorld world(5, {}, Vec2::Zero(), {});
  for (int k = 0; k < 300; ++k) {
    const StampNs t = static_cast<StampNs>(k) * kStep;
    if (k % 10 == 0) agent.onGnss({t + 1, true, Vec2::Zero(), 0.5});
    agent.onImu(world.imu(t));
  }
  // THEN nothing has started while the fixes were valid
  EXPECT_EQ(agent.diagnostics().mission_leg, -1);
  EXPECT_EQ(agent.diagnostics().plan_velocity_mps, Vec2::Zero());
  // WHEN the first sample without a fix arrives, and the next IMU sample
  agent.onGnss({3 * 1'000'000'000LL + 1, false, Vec2::Zero(), 0.5});
  const VelocityCommand cmd = agent.onImu(world.imu(3 * 1'000'000'000LL + kStep));
  // THEN the first leg is flown
  EXPECT_EQ(agent.diagnostics().mission_leg, 0);
  EXPECT_EQ(cmd.velocity_mps, Vec2(1, 0));
}

TEST(AgentMission, WithALimitedFieldOfViewTheAgentTurnsToTheDirectionOfTravel) {
  // GIVEN two agents with 240 deg sensors heading 0.7 rad (FocalWorld), one with a plan north from 0 s
  AgentConfig with = withPlan({{Vec2(0, 3), 10.0}});
  with.sensor.fov_deg = 240.0;
  AgentConfig without = with;
  without.mission.legs.clear();
  Agent moving(with), hovering(without);
  FocalWorld world(5, {}, Vec2::Zero(), {});
  const ImuSample s = world.imu(kStep);
  // THEN the one on the move turns counter-clockwise towards north (90 deg), the other clockwise to facing_deg 0
  EXPECT_EQ(moving.onImu(s).yaw_rate_radps, with.control.max_yaw_rate_radps);
  EXPECT_EQ(hovering.onImu(s).yaw_rate_radps, -without.control.max_yaw_rate_radps);
}

TEST(AgentMission, AStandaloneUavFollowsThePlanFromWhereItStartedOnItsOwnEstimate) {
  // GIVEN a standalone UAV with fixes throughout and a plan of 10 s east at 2 m/s from 20 s
  AgentConfig cfg = withPlan({{Vec2(2, 0), 10.0}}, MissionStart::kTime, 20.0);
  cfg.mode = Mode::kStandalone;
  Agent agent(cfg);
  FocalWorld world(9, {}, Vec2(1, 1), {});
  std::mt19937_64 rng(4);
  std::normal_distribution<double> fix(0.0, 0.3);
  Vec2 u = Vec2::Zero();
  Vec2 at_start = Vec2::Zero();
  for (long k = 0; k < 6000; ++k) {
    const StampNs t = k * kStep;
    world.step(0.01, u);
    if (k == 2000) at_start = world.p;
    if (k % 10 == 0) agent.onGnss({t + 1, true, world.p + Vec2(fix(rng), fix(rng)), 0.3});
    u = agent.onImu(world.imu(t)).velocity_mps;
  }
  // THEN 30 s after the plan ended it holds 20 m east of where it was at the start (gusts move it by ~0.5 m)
  EXPECT_LT((world.p - (at_start + Vec2(20, 0))).norm(), 1.5);
}

TEST(AgentMission, ARestartOfTheImuClockEndsTheMissionInAHold) {
  // GIVEN an agent 2 s into a 60 s leg
  Agent agent(withPlan({{Vec2(2, 0), 60.0}}));
  FocalWorld world(5, {}, Vec2::Zero(), {});
  for (int k = 0; k < 200; ++k) agent.onImu(world.imu(static_cast<StampNs>(k) * kStep));
  ASSERT_EQ(agent.diagnostics().plan_velocity_mps, Vec2(2, 0));
  // WHEN the IMU's clock restarts from 1 s (a producer reboot) and the agent re-synchronises to it
  VelocityCommand cmd;
  for (int k = 0; k < 10; ++k) cmd = agent.onImu(world.imu(1'000'000'000LL + k * kStep));
  // THEN the plan's time means nothing any more: the mission is ended, counted, and the agent holds
  EXPECT_TRUE(agent.diagnostics().mission_aborted);
  EXPECT_EQ(agent.diagnostics().plan_velocity_mps, Vec2::Zero());
  EXPECT_EQ(cmd.velocity_mps, Vec2::Zero());
}

MissionCommand goFor(const Vec2& velocity, double duration_s) {
  MissionCommand c;
  c.legs = {{MissionCommandLeg::Kind::kVelocity, velocity, duration_s, 0.0}};
  return c;
}

TEST(AgentMission, AGroundCommandIsFlownFromTheNextImuSampleThenEndsInAHold) {
  // GIVEN an agent with no plan, hovering alone for 1 s
  Agent agent{AgentConfig{}};
  FocalWorld world(7, {}, Vec2::Zero(), {});
  for (int k = 0; k < 100; ++k) ASSERT_EQ(agent.onImu(world.imu(k * kStep)).velocity_mps, Vec2::Zero());
  // WHEN the ground sends "east at 1.5 m/s for 2 s" between two IMU samples
  ASSERT_TRUE(agent.commandMission(goFor(Vec2(1.5, 0), 2.0)));
  // THEN the very next sample's command flies it, for 2 s, and then the agent holds
  for (int k = 100; k < 400; ++k) {
    const Vec2 expected = k < 300 ? Vec2(1.5, 0) : Vec2::Zero();
    ASSERT_EQ(agent.onImu(world.imu(k * kStep)).velocity_mps, expected) << "step " << k;
  }
  EXPECT_EQ(agent.diagnostics().mission_commands, 1u);
  EXPECT_EQ(agent.diagnostics().mission_command_stamp_ns, 100 * kStep);
}

TEST(AgentMission, AGroundHoldStopsAPlanMidLegAndAnotherCommandGoesOnFromThere) {
  // GIVEN an agent 3 s into a 60 s leg east at 2 m/s
  Agent agent(withPlan({{Vec2(2, 0), 60.0}}));
  FocalWorld world(8, {}, Vec2::Zero(), {});
  for (int k = 0; k < 300; ++k) agent.onImu(world.imu(k * kStep));
  // WHEN the ground says hold
  MissionCommand hold;
  hold.hold = true;
  ASSERT_TRUE(agent.commandMission(hold));
  // THEN the next sample commands a hover, and the plan is in its hold
  EXPECT_EQ(agent.onImu(world.imu(300 * kStep)).velocity_mps, Vec2::Zero());
  EXPECT_EQ(agent.diagnostics().plan_velocity_mps, Vec2::Zero());
  // AND fifty commands later the plan is still one flown leg and the command's: it does not grow with them
  for (int n = 0; n < 50; ++n) {
    ASSERT_TRUE(agent.commandMission(goFor(Vec2(0, n % 2 ? 1.0 : -1.0), 5.0)));
    agent.onImu(world.imu((301 + n) * kStep));
  }
  EXPECT_EQ(agent.diagnostics().mission_leg, 1);
  EXPECT_EQ(agent.diagnostics().plan_velocity_mps, Vec2(0, 1));
  EXPECT_EQ(agent.diagnostics().mission_commands, 51u);
}

TEST(AgentMission, AnUnflyableGroundCommandIsRefusedCountedAndChangesNothing) {
  // GIVEN an agent flying east at 2 m/s (the plan's limit mission.max_speed_mps is 5 m/s)
  Agent agent(withPlan({{Vec2(2, 0), 60.0}}));
  FocalWorld world(9, {}, Vec2::Zero(), {});
  for (int k = 0; k < 100; ++k) agent.onImu(world.imu(k * kStep));
  // WHEN the ground sends a command too fast, one with a NaN and one with neither legs nor a hold
  EXPECT_FALSE(agent.commandMission(goFor(Vec2(6, 0), 1.0)));
  EXPECT_FALSE(agent.commandMission(goFor(Vec2(std::nan(""), 0), 1.0)));
  EXPECT_FALSE(agent.commandMission(MissionCommand{}));
  // THEN each is counted and the plan flies on
  EXPECT_EQ(agent.diagnostics().mission_commands_refused, 3u);
  EXPECT_EQ(agent.onImu(world.imu(100 * kStep)).velocity_mps, Vec2(2, 0));
  EXPECT_EQ(agent.diagnostics().mission_commands, 0u);
}

}  // namespace
}  // namespace swa::agent
