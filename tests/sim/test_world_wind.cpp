// The mean wind and drag (issue #44): the velocity loop holds the path, the attitude leans into the air's push, the
// tilt shows the thrust only, and the accelerometer shows every push.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "swa/sim/imu_model.h"
#include "swa/sim/world.h"
#include "world_support.h"

namespace swa::sim {
namespace {

using agent::Vec2;

// What the agent reads from each part of a sample, in the world frame (its heading is the true one here).
Vec2 tiltAcceleration(const agent::ImuSample& imu, double q_c) {
  return agent::rotation(imu.heading_rad) * (q_c * Vec2(imu.pitch_rad, imu.roll_rad));
}
Vec2 accelerometerAcceleration(const agent::ImuSample& imu) {
  return agent::rotation(imu.heading_rad) * agent::levelAcceleration(*imu.accelerometer);
}

// Error-free sensors, so that a reading is the physics alone.
Scenario exactSensors(int n) {
  Scenario s = testing::calmScenario(n, 17);
  s.dynamics.failsafe_timeout_s = std::numeric_limits<double>::infinity();  // hover on the zero setpoint
  s.imu = testing::exactImu(s.imu);
  return s;
}

TEST(WorldWind, TheWindBlowsFromWhereItsDirectionSaysAndTurnsAtItsRate) {
  // GIVEN a 5 m/s wind from the north (0 deg), turning clockwise at 1 deg/s
  Scenario s = exactSensors(1);
  s.wind.mean_mps = 5.0;
  s.wind.direction_deg = 0.0;
  s.wind.turn_rate_dps = 1.0;
  World w(s);
  // THEN at first it blows south
  EXPECT_NEAR(w.truth()[0].wind_mps.x(), 0.0, 1e-12);
  EXPECT_NEAR(w.truth()[0].wind_mps.y(), -5.0, 1e-12);
  // AND 90 s later it comes from the east and blows west
  for (int k = 0; k < 9000; ++k) w.step();
  EXPECT_NEAR(w.truth()[0].wind_mps.x(), -5.0, 1e-9);
  EXPECT_NEAR(w.truth()[0].wind_mps.y(), 0.0, 1e-9);
}

TEST(WorldWind, TheWindChangesTheAttitudeNotThePath) {
  // GIVEN two swarms alike but for an 8 m/s wind in one, both with gusts, flying the same commands
  Scenario s = exactSensors(3);
  s.wind.gust_std = 0.2;
  World calm(s);
  s.wind.mean_mps = 8.0;
  s.wind.direction_deg = 200.0;
  World windy(s);
  for (int k = 0; k < 3000; ++k) {
    for (int i = 0; i < 3; ++i) {
      agent::VelocityCommand cmd;
      cmd.velocity_mps = Vec2(std::sin(0.01 * k + i), 0.5);
      calm.command(i, cmd);
      windy.command(i, cmd);
    }
    calm.step();
    windy.step();
  }
  for (int i = 0; i < 3; ++i) {
    // THEN the paths are the same bit for bit (the velocity loop holds the command against the drag)
    EXPECT_EQ(calm.truth()[i].position_m, windy.truth()[i].position_m);
    EXPECT_EQ(calm.truth()[i].velocity_mps, windy.truth()[i].velocity_mps);
    // AND the accelerometer reads the same, while the tilt differs by the drag of the wind, k w
    const auto& a = *calm.sensors()[i].imu;
    const auto& b = *windy.sensors()[i].imu;
    EXPECT_NEAR((accelerometerAcceleration(a) - accelerometerAcceleration(b)).norm(), 0.0, 1e-9);
    const Vec2 tilt_shift = tiltAcceleration(b, 6.35) - tiltAcceleration(a, 6.35);
    const Vec2 expected = -s.dynamics.drag_per_s * windy.truth()[i].wind_mps;
    EXPECT_NEAR((tilt_shift - expected).norm(), 0.0, 1e-9) << i;
  }
}

TEST(WorldWind, AUavHoldingStillInTheWindLeansIntoItAndOnlyTheTiltSaysItAccelerates) {
  // GIVEN a UAV hovering without gusts in a 5 m/s westerly (blowing east), drag 0.15 1/s, heading 1 rad
  Scenario s = exactSensors(1);
  s.dynamics.heading = HeadingMode::kRandom;
  s.wind.mean_mps = 5.0;
  s.wind.direction_deg = 270.0;
  World w(s);
  for (int k = 0; k < 100; ++k) w.step();
  const UavTruth& t = w.truth()[0];
  const agent::ImuSample& imu = *w.sensors()[0].imu;
  // THEN it does not move
  EXPECT_EQ(t.velocity_mps, Vec2::Zero());
  // AND its thrust pushes west against the drag, k w = 0.75 m/s^2, which is what the tilt reads as acceleration
  EXPECT_NEAR(t.thrust_mps2.x(), -0.75, 1e-12);
  EXPECT_NEAR(t.thrust_mps2.y(), 0.0, 1e-12);
  EXPECT_NEAR((tiltAcceleration(imu, 6.35) - t.thrust_mps2).norm(), 0.0, 1e-12);
  // AND the attitude leans west by atan(0.75 / g), while the accelerometer, turned by it, reads no acceleration
  const agent::Vec3 up =
      agent::tiltRotation(imu.accelerometer->roll_rad, imu.accelerometer->pitch_rad) * agent::Vec3::UnitZ();
  const Vec2 lean = agent::rotation(t.heading_rad) * Vec2(up.x(), up.y());
  EXPECT_NEAR(std::atan2(-lean.x(), up.z()), std::atan(0.75 / agent::kStandardGravity_mps2), 1e-12);
  EXPECT_NEAR(lean.y(), 0.0, 1e-12);
  EXPECT_NEAR(accelerometerAcceleration(imu).norm(), 0.0, 1e-12);
  // AND the accelerometer itself feels the wind's push along the body's x-y plane (the rotor drag a real one shows)
  const agent::Vec3& f = imu.accelerometer->specific_force_body_mps2;
  EXPECT_NEAR(std::hypot(f.x(), f.y()), 0.75 * agent::kStandardGravity_mps2 / std::hypot(0.75, 9.80665), 1e-9);
  EXPECT_NEAR(f.norm(), agent::kStandardGravity_mps2, 1e-9);  // thrust and drag together hold it up
}

TEST(WorldWind, AGustPushesTheUavWithoutTiltingIt) {
  // GIVEN a hovering UAV in gusts, calm mean air, no drag
  Scenario s = exactSensors(1);
  s.wind.gust_std = 0.3;
  s.dynamics.drag_per_s = 0.0;
  World w(s);
  double gust_seen_by_tilt = 0.0;
  double acceleration_missed_by_accelerometer = 0.0;
  double gust_size = 0.0;
  for (int k = 0; k < 2000; ++k) {
    w.step();
    const UavTruth& t = w.truth()[0];
    const agent::ImuSample& imu = *w.sensors()[0].imu;
    // THEN the tilt shows the thrust, the achieved acceleration less the gust
    gust_seen_by_tilt =
        std::max(gust_seen_by_tilt, (tiltAcceleration(imu, 6.35) - (t.acceleration_mps2 - t.gust_mps2)).norm());
    // AND the accelerometer shows the achieved acceleration, gust included
    acceleration_missed_by_accelerometer =
        std::max(acceleration_missed_by_accelerometer, (accelerometerAcceleration(imu) - t.acceleration_mps2).norm());
    gust_size = std::max(gust_size, t.gust_mps2.norm());
  }
  EXPECT_LT(gust_seen_by_tilt, 1e-12);
  EXPECT_LT(acceleration_missed_by_accelerometer, 1e-12);
  EXPECT_GT(gust_size, 0.3);  // the gusts were there to be missed
}

TEST(WorldWind, TheAttitudeErrorIsAConstantBiasOfGravityTimesItAndTheAccelerometerHasItsOwn) {
  // GIVEN 300 hovering UAVs with attitude error std 0.01 rad and no other error
  Scenario s = exactSensors(300);
  s.formation.spacing_m = 3.0;
  s.imu.attitude_error_std_rad = 0.01;
  World w(s);
  std::vector<Vec2> first(300);
  double sum2 = 0.0;
  for (int k = 0; k < 20; ++k) {
    w.step();
    for (std::size_t i = 0; i < 300; ++i) {
      const Vec2 bias = accelerometerAcceleration(*w.sensors()[i].imu) - w.truth()[i].acceleration_mps2;
      if (k == 0) {
        first[i] = bias;
        sum2 += bias.squaredNorm();
      } else {
        // THEN each UAV's bias stays what it was
        EXPECT_NEAR((bias - first[i]).norm(), 0.0, 1e-12);
      }
    }
  }
  // AND its spread per axis is g x 0.01 = 0.098 m/s^2 (+-12 %: 600 draws)
  EXPECT_NEAR(std::sqrt(sum2 / 600.0), agent::kStandardGravity_mps2 * 0.01, 0.012);
}

TEST(WorldWind, TheAccelerometersNoiseHasItsConfiguredSpreadAndLeavesTheTiltAlone) {
  // GIVEN one hovering UAV with accelerometer noise 0.35 m/s^2, and its twin without
  Scenario s = exactSensors(1);
  World quiet(s);
  s.imu.accel_noise_std_mps2 = 0.35;
  World noisy(s);
  double sum2 = 0.0;
  for (int k = 0; k < 5000; ++k) {
    quiet.step();
    noisy.step();
    const agent::ImuSample& a = *quiet.sensors()[0].imu;
    const agent::ImuSample& b = *noisy.sensors()[0].imu;
    sum2 += (b.accelerometer->specific_force_body_mps2 - a.accelerometer->specific_force_body_mps2).squaredNorm();
    // THEN the tilt and the heading are untouched (the accelerometer has its own random streams)
    ASSERT_EQ(a.pitch_rad, b.pitch_rad);
    ASSERT_EQ(a.heading_rad, b.heading_rad);
  }
  // AND the noise per axis has std 0.35 (+-5 %: 15000 draws)
  EXPECT_NEAR(std::sqrt(sum2 / 15000.0), 0.35, 0.0175);
}

}  // namespace
}  // namespace swa::sim
