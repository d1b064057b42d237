#include <cmath>

#include <gtest/gtest.h>

#include "swa/agent/agent.h"
#include "swa/agent/geometry.h"

namespace swa::agent {
namespace {

TEST(Geometry, NeighbourStraightAheadOfUavHeadingEastIsEast) {
  // GIVEN a UAV heading east (world x = east, heading 0) and a neighbour 5 m straight ahead in its body frame
  const Vec2 ahead(5.0, 0.0);
  // WHEN rotated into the stable frame
  const Vec2 s = rotation(0.0) * ahead;
  // THEN it is 5 m east
  EXPECT_NEAR(s.x(), 5.0, 1e-12);
  EXPECT_NEAR(s.y(), 0.0, 1e-12);
}

TEST(Geometry, NeighbourAheadOfUavHeadingNorthIsNorthAndLeftIsWest) {
  // GIVEN heading pi/2 (body x points north, counter-clockwise from east)
  const Mat2 R = rotation(M_PI / 2);
  // THEN ahead maps to north and body-left (+y) to west
  const Vec2 ahead = R * Vec2(5.0, 0.0);
  const Vec2 left = R * Vec2(0.0, 3.0);
  EXPECT_NEAR(ahead.x(), 0.0, 1e-12);
  EXPECT_NEAR(ahead.y(), 5.0, 1e-12);
  EXPECT_NEAR(left.x(), -3.0, 1e-12);
  EXPECT_NEAR(left.y(), 0.0, 1e-12);
}

TEST(Geometry, AgentRotatesDetectionsByItsImuHeading) {
  // GIVEN an agent whose IMU reports heading 30 deg, and one identified neighbour 8 m straight ahead
  AgentConfig cfg;
  cfg.focal.imu_source = ImuSource::kTilt;  // a tilt-only sample below
  Agent agent{cfg};
  const double psi = 30.0 * M_PI / 180.0;
  agent.onImu({0, 0.0, 0.0, psi});
  DetectionSet set;
  set.stamp_ns = 1;
  set.detections.push_back({7, Vec2(8.0, 0.0), std::nullopt});
  // WHEN the detection set is processed
  agent.onDetections(set);
  // THEN the track sits 8 m along the 30 deg bearing in the stable frame
  const Track* t = agent.bank().find(7);
  ASSERT_NE(t, nullptr);
  EXPECT_NEAR(t->position().x(), 8.0 * std::cos(psi), 1e-9);
  EXPECT_NEAR(t->position().y(), 8.0 * std::sin(psi), 1e-9);
}

TEST(Geometry, TiltToAccelerationFollowsDesignConvention) {
  // GIVEN heading pi/2 and pitch 0.1 rad (body-x acceleration q_c * 0.1 by DESIGN §3.4), no roll
  AgentConfig cfg;
  cfg.mode = Mode::kStandalone;
  cfg.focal.imu_source = ImuSource::kTilt;
  Agent agent{cfg};
  agent.onGnss({0, true, Vec2(0, 0), 0.5});
  // WHEN many IMU samples arrive (the acceleration state converges to the measurement)
  for (int k = 1; k <= 300; ++k) agent.onImu({k * 10'000'000LL, 0.0, 0.1, M_PI / 2});
  // THEN the estimated acceleration points north (+y) with magnitude near q_c * 0.1 = 0.635 m/s^2
  const Vec2 a = agent.absolute().acceleration();
  EXPECT_NEAR(a.x(), 0.0, 0.05);
  EXPECT_NEAR(a.y(), 0.635, 0.1);
}

TEST(Geometry, AccelerometerSourceTurnsTheSpecificForceLevelAndIgnoresTheTiltWhileItHasOne) {
  // GIVEN an agent told to use the accelerometer, heading pi/2
  AgentConfig cfg;
  cfg.mode = Mode::kStandalone;
  cfg.focal.imu_source = ImuSource::kAccelerometer;
  Agent agent{cfg};
  agent.onGnss({0, true, Vec2(0, 0), 0.5});
  // WHEN its samples carry a tilt that says "accelerating east" (as in a wind), and an accelerometer leaning 0.1
  // rad forward whose specific force, turned level, is 0.5 m/s^2 forward (body x) and g up
  AccelerometerSample acc;
  acc.pitch_rad = 0.1;
  acc.specific_force_body_mps2 = tiltRotation(0.0, 0.1).transpose() * Vec3(0.5, 0.0, kStandardGravity_mps2);
  for (int k = 1; k <= 300; ++k) {
    const VelocityCommand c = agent.onImu({k * 10'000'000LL, 0.0, -0.2, M_PI / 2, acc});
    ASSERT_TRUE(c.fresh);
  }
  // THEN the estimated acceleration is the accelerometer's, 0.5 m/s^2 north, not the tilt's
  const Vec2 a = agent.absolute().acceleration();
  EXPECT_NEAR(a.x(), 0.0, 0.05);
  EXPECT_NEAR(a.y(), 0.5, 0.05);
  EXPECT_EQ(agent.diagnostics().tilt_fallbacks, 0u);
  // AND a sample without an accelerometer is answered, read from its tilt, and counted as such (not refused: a
  // vehicle whose accelerometer stream starts after its attitude must not go unanswered)
  const VelocityCommand fallback = agent.onImu({301 * 10'000'000LL, 0.0, 0.1, M_PI / 2});
  EXPECT_TRUE(fallback.fresh);
  EXPECT_EQ(agent.diagnostics().tilt_fallbacks, 1u);
  EXPECT_EQ(agent.diagnostics().rejected.total(), 0u);
  // AND one whose specific force is beyond a MEMS accelerometer's range (16 g) is refused as implausible, and one
  // that is not finite as non-finite
  acc.specific_force_body_mps2 = Vec3(0.0, 0.0, 17.0 * kStandardGravity_mps2);
  EXPECT_FALSE(agent.onImu({302 * 10'000'000LL, 0.0, 0.0, M_PI / 2, acc}).fresh);
  EXPECT_EQ(agent.diagnostics().rejected.implausible, 1u);
  acc.specific_force_body_mps2 = Vec3(0.0, std::nan(""), 9.8);
  EXPECT_FALSE(agent.onImu({303 * 10'000'000LL, 0.0, 0.0, M_PI / 2, acc}).fresh);
  EXPECT_EQ(agent.diagnostics().rejected.nonfinite, 1u);
}

TEST(Geometry, TiltRotationLeansBodyZByPitchTowardsXAndByRollTowardsY) {
  const Vec3 z = tiltRotation(0.2, 0.3) * Vec3::UnitZ();
  EXPECT_NEAR(z.x(), std::sin(0.3) * std::cos(0.2), 1e-15);
  EXPECT_NEAR(z.y(), std::sin(0.2), 1e-15);
  EXPECT_NEAR(z.z(), std::cos(0.3) * std::cos(0.2), 1e-15);
  // AND it is a rotation
  const Mat3 r = tiltRotation(-0.7, 1.1);
  EXPECT_NEAR((r * r.transpose() - Mat3::Identity()).norm(), 0.0, 1e-15);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-15);
}

}  // namespace
}  // namespace swa::agent
