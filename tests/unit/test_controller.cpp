#include <cmath>

#include <gtest/gtest.h>

#include "focal_scenario.h"
#include "swa/agent/agent.h"
#include "swa/agent/controller.h"

namespace swa::agent {
namespace {

using testing::FocalWorld;

TEST(HeadingControl, AnAllRoundSensorNeverTurnsTheHeading) {
  const SensorConfig all_round;
  const ControlConfig c;
  for (double h : {-3.0, -1.0, 0.0, 0.7, 3.1}) EXPECT_EQ(headingRate(h, all_round, c), 0.0);
}

TEST(HeadingControl, ALimitedSensorTurnsItsAxisToTheFacingTheShortWayWithinTheLimit) {
  SensorConfig sensor;
  sensor.fov_deg = 240.0;
  sensor.mount_deg = 30.0;  // the axis is 30 deg left of body x
  ControlConfig c;
  c.facing_deg = 90.0;  // north: the body must head 60 deg
  c.k_yaw = 2.0;
  c.max_yaw_rate_radps = 0.5;
  const double wanted = 60.0 * M_PI / 180.0;
  // small errors: proportional, towards the wanted heading
  EXPECT_NEAR(headingRate(wanted - 0.1, sensor, c), 0.2, 1e-12);
  EXPECT_NEAR(headingRate(wanted + 0.05, sensor, c), -0.1, 1e-12);
  EXPECT_EQ(headingRate(wanted, sensor, c), 0.0);
  // large errors: saturated, and the shorter way round across +-pi
  EXPECT_EQ(headingRate(wanted - 2.0, sensor, c), 0.5);
  EXPECT_EQ(headingRate(wanted + 2.0, sensor, c), -0.5);
  EXPECT_EQ(headingRate(wanted + 4.0, sensor, c), 0.5);  // 4 rad clockwise is 2.28 rad counter-clockwise
  // a heading that is not a number never gives a command that is not
  EXPECT_EQ(headingRate(std::nan(""), sensor, c), 0.0);
}

TEST(HeadingControl, TheAgentsCommandCarriesTheRateOnlyWithALimitedSensor) {
  AgentConfig config;
  config.focal.imu_source = ImuSource::kTilt;  // the samples below are tilt-only
  ImuSample imu;
  imu.stamp_ns = 10'000'000;
  imu.heading_rad = 1.0;
  EXPECT_EQ(Agent(config).onImu(imu).yaw_rate_radps, 0.0);
  config.sensor.fov_deg = 180.0;
  const VelocityCommand cmd = Agent(config).onImu(imu);
  EXPECT_EQ(cmd.yaw_rate_radps, -config.control.max_yaw_rate_radps);  // facing east, 1 rad left of it: turn right
}

TEST(Controller, StableSignPointsFromEstimateTowardsFrameOrigin) {
  // GIVEN the UAV estimated 3 m east of its frame origin, at rest
  ControlConfig paper;
  paper.k_p = 0.5;  // Table I
  const Vec2 v = formationVelocity(Vec2(3.0, 0.0), Vec2::Zero(), paper);
  // THEN the command is west at k_p * 3 = 1.5 m/s (the paper's literal sign would push east, away)
  EXPECT_DOUBLE_EQ(v.x(), -1.5);
  EXPECT_DOUBLE_EQ(v.y(), 0.0);
  // AND moving east at 1 m/s adds k_v = 0.63 of damping
  EXPECT_DOUBLE_EQ(formationVelocity(Vec2::Zero(), Vec2(1.0, 0.0), ControlConfig{}).x(), -0.63);
}

TEST(Controller, SaturationKeepsDirectionAndClampsNorm) {
  const Vec2 s = saturate(Vec2(30.0, -40.0), 2.0);
  EXPECT_NEAR(s.norm(), 2.0, 1e-15);
  EXPECT_NEAR(s.x() / s.y(), -0.75, 1e-15);
  EXPECT_EQ(saturate(Vec2(0.3, 0.4), 2.0), Vec2(0.3, 0.4));
  EXPECT_EQ(saturate(Vec2(NAN, 1.0), 2.0), Vec2::Zero());
}

TEST(Controller, SingleAgentWithFixedNeighboursConvergesToItsFrameOriginWithinSaturation) {
  // GIVEN three hovering neighbours on a circle of r = 10 m around (50, 20), and the focal UAV starting 25 m away
  const Vec2 origin(50.0, 20.0);
  std::vector<Vec2> group;
  for (double deg : {100.0, 220.0, 340.0})
    group.push_back(origin + 10.0 * Vec2(std::cos(deg * M_PI / 180), std::sin(deg * M_PI / 180)));
  FocalWorld::Options opt;
  FocalWorld world(11, group, origin + Vec2(20.0, -15.0), opt);
  // All three define the frame (k nearest, unweighted): the controller is under test, not the neighbourhood rule.
  // (Gabriel would keep only the nearest of the group seen from outside it, and the UAV would join at r from that
  // one, a valid formation slot, but not the circle centre this test checks against.)
  AgentConfig cfg;
  cfg.formation.neighbourhood = NeighbourhoodRule::kKNearest;
  cfg.formation.far_neighbour_weight = 1.0;
  Agent agent{cfg};
  const double dt = 0.01;
  Vec2 u = Vec2::Zero();
  double max_cmd = 0.0, saturated_steps = 0;
  double dist_at_10s = 0.0;

  // WHEN the closed loop runs for 60 s (IMU 100 Hz, detections 10 Hz)
  for (int k = 0; k < 6000; ++k) {
    const StampNs t = static_cast<StampNs>(k) * 10'000'000;
    world.step(dt, u);
    if (k % 10 == 0) agent.onDetections(world.detections(t));
    const VelocityCommand cmd = agent.onImu(world.imu(t));
    u = cmd.velocity_mps;
    max_cmd = std::max(max_cmd, u.norm());
    saturated_steps += u.norm() > 2.0 - 1e-9;
    if (k == 1000) dist_at_10s = (world.p - origin).norm();
  }

  // THEN it sits at the circle centre (within noise), never exceeded 2 m/s, and started out saturated
  EXPECT_LT((world.p - origin).norm(), 0.5);
  EXPECT_LT(dist_at_10s, 15.0);  // it moved towards the origin from 25 m, i.e. the sign is the stable one
  EXPECT_LE(max_cmd, 2.0 + 1e-12);
  EXPECT_GT(saturated_steps, 100);
  EXPECT_EQ(agent.diagnostics().stage, Stage::kTracking);
  EXPECT_EQ(agent.diagnostics().neighbour_count, 3);
}

}  // namespace
}  // namespace swa::agent
