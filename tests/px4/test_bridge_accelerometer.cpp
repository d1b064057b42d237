// The accelerometer through the autopilots (issue #44): the simulator's sample as PX4's sensor_combined +
// vehicle_attitude (or ArduPilot's IMU message), read back by the bridge, gives the agent the same level acceleration
// the simulator meant, for any attitude and heading; and PX4's two topics are paired by time, never with a stale force.

#include <cmath>

#include <gtest/gtest.h>

#include "../sim/world_support.h"
#include "swa/autopilot/bridge_core.h"
#include "swa/px4/accelerometer.h"
#include "swa/px4/frames.h"
#include "swa/sim/imu_model.h"
#include "swa/wire/ardupilot.h"
#include "swa/wire/px4.h"

namespace swa {
namespace {

using agent::Vec2;
using agent::Vec3;

// A sample as the simulator makes it: a UAV accelerating at `a` while its thrust (drag, wind) differs, heading `psi`.
agent::ImuSample simulated(const Vec2& a, const Vec2& thrust, double psi) {
  const sim::ImuSetup setup = sim::testing::exactImu();
  sim::ImuModel model(setup, 6.35, sim::ImuModel::Streams::of(1, 0));
  return model.sample(20'000'000, a, thrust, psi);
}

Vec2 worldAcceleration(const agent::ImuSample& s) {
  return agent::rotation(s.heading_rad) * agent::levelAcceleration(*s.accelerometer);
}

TEST(BridgeAccelerometer, Px4sTwoTopicsGiveTheAgentTheAccelerationTheSimulatorMeant) {
  for (const double psi : {0.0, 0.9, -2.2, M_PI}) {
    for (const Vec2& thrust : {Vec2(0.0, 0.0), Vec2(-0.75, 0.3), Vec2(2.0, -1.5)}) {
      // GIVEN a simulated sample: accelerating at (0.4, -0.2) m/s^2 while the thrust pushes differently (drag)
      const Vec2 a(0.4, -0.2);
      const agent::ImuSample s = simulated(a, thrust, psi);
      // WHEN the stand-in sends it as PX4 would (the accelerometer's attitude as vehicle_attitude, the force FRD)
      const auto att = wire::vehicleAttitude(
          20'000,
          px4::quaternionOf(px4::px4Euler({s.accelerometer->roll_rad, s.accelerometer->pitch_rad, s.heading_rad})));
      const auto sc = wire::sensorCombined(20'000, px4::flippedBody(s.accelerometer->specific_force_body_mps2));
      px4::AccelerometerPairing pairing;
      const float f[3] = {sc.accelerometer_m_s2()[0], sc.accelerometer_m_s2()[1], sc.accelerometer_m_s2()[2]};
      ASSERT_TRUE(pairing.onSensorCombined(sc.timestamp(), sc.accelerometer_timestamp_relative(), f));
      const auto r = pairing.pairWith(att.timestamp_sample());
      ASSERT_TRUE(r.has_value());
      autopilot::BridgeCore core{autopilot::BridgeConfig{}};
      const auto imu =
          core.onAttitude(att.timestamp(), wire::quaternionOf(att), 0.0, ardupilot::SpecificForce{r->x, r->y, r->z});
      // THEN the agent's sample carries the accelerometer, and turned level it is the simulator's acceleration
      // (float32 on PX4's side: a few 1e-6 m/s^2)
      ASSERT_TRUE(imu && imu->accelerometer);
      EXPECT_NEAR((worldAcceleration(*imu) - a).norm(), 0.0, 1e-5) << psi << " " << thrust.transpose();
      // AND the tilt in the same sample is the vehicle's attitude (the lean into the thrust)
      EXPECT_NEAR(imu->pitch_rad, s.accelerometer->pitch_rad, 1e-6);
      EXPECT_NEAR(imu->roll_rad, s.accelerometer->roll_rad, 1e-6);
    }
  }
}

TEST(BridgeAccelerometer, ArduPilotsImuMessageGivesTheAgentTheAccelerationTheSimulatorMeant) {
  // GIVEN a simulated sample leaning into a 5 m/s wind (thrust -0.75 m/s^2 east) while holding still, heading 1 rad
  const agent::ImuSample s = simulated(Vec2::Zero(), Vec2(-0.75, 0.0), 1.0);
  const px4::Quaternion q =
      px4::quaternionOf(px4::px4Euler({s.accelerometer->roll_rad, s.accelerometer->pitch_rad, s.heading_rad}));
  const Vec3 frd = px4::flippedBody(s.accelerometer->specific_force_body_mps2);
  // WHEN sent as ArduPilot's IMU message and read back by the bridge
  const sensor_msgs::msg::Imu m = wire::imuMessage(20'000, q, ardupilot::QuaternionLayout::kRos,
                                                   ardupilot::SpecificForce{frd.x(), frd.y(), frd.z()});
  autopilot::BridgeCore core{autopilot::BridgeConfig{}};
  const auto imu =
      core.onAttitude(20'000, wire::attitudeOf(m, ardupilot::QuaternionLayout::kRos), 0.0, wire::specificForceOf(m));
  // THEN the agent reads no acceleration, where the tilt alone says 0.75 m/s^2 upwind
  ASSERT_TRUE(imu && imu->accelerometer);
  EXPECT_NEAR(worldAcceleration(*imu).norm(), 0.0, 1e-12);
  EXPECT_GT(std::hypot(imu->pitch_rad, imu->roll_rad), 0.07);
}

TEST(BridgeAccelerometer, Px4sReadingsPairOnlyWithAnAttitudeOfTheirInstant) {
  px4::AccelerometerPairing p;
  const float g[3] = {0.0f, 0.0f, -9.8f};
  // GIVEN nothing yet: no pair
  EXPECT_FALSE(p.pairWith(1'000'000).has_value());
  // WHEN a reading of 1.000 s (timestamp 0.998 s + 2 ms relative) arrives
  ASSERT_TRUE(p.onSensorCombined(998'000, 2'000, g));
  // THEN it pairs with attitudes up to 15 ms away, and not beyond
  EXPECT_TRUE(p.pairWith(1'015'000).has_value());
  EXPECT_TRUE(p.pairWith(985'000).has_value());
  EXPECT_FALSE(p.pairWith(1'015'001).has_value());
  EXPECT_EQ(p.pairWith(1'000'000)->z, -9.8f);
  // AND an older reading arriving late does not replace it
  const float late[3] = {1.0f, 0.0f, -9.8f};
  ASSERT_TRUE(p.onSensorCombined(900'000, 0, late));
  EXPECT_EQ(p.pairWith(1'000'000)->x, 0.0);
  // AND readings PX4 marks invalid, or not finite, are refused and counted
  const float nan[3] = {std::nanf(""), 0.0f, 0.0f};
  EXPECT_FALSE(p.onSensorCombined(1'100'000, 2147483647, g));
  EXPECT_FALSE(p.onSensorCombined(1'100'000, 0, nan));
  EXPECT_FALSE(p.onSensorCombined(10, -20, g));
  EXPECT_EQ(p.invalid(), 3u);
  EXPECT_EQ(p.received(), 5u);
  EXPECT_FALSE(p.pairWith(1'100'000).has_value());  // the newest valid reading is 100 ms old
}

TEST(BridgeAccelerometer, WithoutAForceTheBridgeGivesATiltOnlySample) {
  autopilot::BridgeCore core{autopilot::BridgeConfig{}};
  const auto imu = core.onAttitude(20'000, px4::Quaternion{}, 0.0);
  ASSERT_TRUE(imu.has_value());
  EXPECT_FALSE(imu->accelerometer.has_value());
}

}  // namespace
}  // namespace swa
