// Determinism: same scenario + same commands = bit-identical world; seeds and streams behave as documented.
#include <algorithm>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "swa/sim/world.h"

namespace swa::sim {
namespace {

using agent::Vec2;

// Everything random switched on at once.
Scenario busyScenario(std::uint64_t seed) {
  Scenario s;
  s.uav_count = 6;
  s.seed = seed;
  s.dynamics.heading_rate_std_radps = 0.05;
  s.wind.common_std = 0.1;
  s.mps.noise_model = MpsNoiseModel::kRangeBearing;
  s.mps.clutter_rate = 1.5;
  s.mps.ids = false;
  s.mps.latency_s = 0.05;
  s.gnss.dropout_start_s = 3.0;
  s.gnss.dropout_end_s = 6.0;
  s.gnss.keep_uavs = {2};
  return s;
}

bool same(const UavTruth& a, const UavTruth& b) {
  return a.id == b.id && a.position_m == b.position_m && a.velocity_mps == b.velocity_mps &&
         a.acceleration_mps2 == b.acceleration_mps2 && a.heading_rad == b.heading_rad && a.gnss_valid == b.gnss_valid &&
         a.failsafe == b.failsafe && a.gust_mps2 == b.gust_mps2;
}

bool same(const agent::Detection& a, const agent::Detection& b) {
  return a.target_id == b.target_id && a.position_body_m == b.position_body_m &&
         a.covariance_m2.has_value() == b.covariance_m2.has_value() &&
         (!a.covariance_m2 || *a.covariance_m2 == *b.covariance_m2);
}

bool same(const UavSensors& a, const UavSensors& b) {
  if (a.imu.has_value() != b.imu.has_value() || a.detections.has_value() != b.detections.has_value() ||
      a.gnss.has_value() != b.gnss.has_value()) {
    return false;
  }
  if (a.imu && (a.imu->stamp_ns != b.imu->stamp_ns || a.imu->roll_rad != b.imu->roll_rad ||
                a.imu->pitch_rad != b.imu->pitch_rad || a.imu->heading_rad != b.imu->heading_rad)) {
    return false;
  }
  if (a.gnss && (a.gnss->stamp_ns != b.gnss->stamp_ns || a.gnss->valid != b.gnss->valid ||
                 a.gnss->position_m != b.gnss->position_m || a.gnss->std_m != b.gnss->std_m)) {
    return false;
  }
  if (a.detections) {
    if (a.detections->stamp_ns != b.detections->stamp_ns ||
        a.detections->detections.size() != b.detections->detections.size()) {
      return false;
    }
    for (std::size_t j = 0; j < a.detections->detections.size(); ++j) {
      if (!same(a.detections->detections[j], b.detections->detections[j])) return false;
    }
  }
  return true;
}

// A command sequence from the test's own seeded generator; some UAVs go silent for a while (failsafe).
void commandRandomly(World& world, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> v(-2.0, 2.0);
  for (int i = 0; i < world.uav_count(); ++i) {
    const double vx = v(rng);
    const double vy = v(rng);
    if (i == 3 && world.step_index() > 200 && world.step_index() < 400) continue;
    agent::VelocityCommand cmd;
    cmd.stamp_ns = world.time_ns();
    cmd.velocity_mps = Vec2(vx, vy);
    world.command(i, cmd);
  }
}

TEST(WorldDeterminism, SameScenarioAndCommandsGiveBitIdenticalTruthSamplesAndEvents) {
  World a(busyScenario(77));
  World b(busyScenario(77));
  std::mt19937_64 rng_a(5), rng_b(5);
  int events = 0;
  for (int k = 0; k < 1000; ++k) {
    for (std::size_t i = 0; i < 6; ++i) {
      ASSERT_TRUE(same(a.truth()[i], b.truth()[i])) << "step " << k << " uav " << i;
      ASSERT_TRUE(same(a.sensors()[i], b.sensors()[i])) << "step " << k << " uav " << i;
    }
    ASSERT_EQ(a.events().size(), b.events().size());
    for (std::size_t e = 0; e < a.events().size(); ++e) {
      EXPECT_EQ(a.events()[e].stamp_ns, b.events()[e].stamp_ns);
      EXPECT_EQ(a.events()[e].kind, b.events()[e].kind);
      EXPECT_EQ(a.events()[e].value, b.events()[e].value);
    }
    events += static_cast<int>(a.events().size());
    commandRandomly(a, rng_a);
    commandRandomly(b, rng_b);
    a.step();
    b.step();
  }
  // The run exercised the event paths too: 5 losses, 5 restorations, failsafe on and off for UAV 3.
  EXPECT_GE(events, 12);
  EXPECT_EQ(a.collisions(), b.collisions());
}

TEST(WorldDeterminism, DifferentSeedGivesADifferentWorld) {
  const World a(busyScenario(77));
  const World b(busyScenario(78));
  int differing = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    differing += !same(a.truth()[i], b.truth()[i]);
    differing += !same(a.sensors()[i], b.sensors()[i]);
  }
  EXPECT_EQ(differing, 12);
}

TEST(WorldDeterminism, TurningOnClutterChangesNoOtherStream) {
  // GIVEN two worlds differing only in the clutter rate, flown with the same commands
  Scenario quiet = busyScenario(31);
  quiet.mps.ids = true;
  quiet.mps.clutter_rate = 0.0;
  Scenario cluttered = quiet;
  cluttered.mps.clutter_rate = 3.0;
  World a(quiet), b(cluttered);
  std::mt19937_64 rng_a(8), rng_b(8);
  int clutter_seen = 0;
  for (int k = 0; k < 500; ++k) {
    commandRandomly(a, rng_a);
    commandRandomly(b, rng_b);
    a.step();
    b.step();
    for (std::size_t i = 0; i < 6; ++i) {
      // THEN truth, IMU and GNSS are bit-identical
      ASSERT_TRUE(same(a.truth()[i], b.truth()[i]));
      UavSensors sa = a.sensors()[i], sb = b.sensors()[i];
      sa.detections.reset();
      sb.detections.reset();
      ASSERT_TRUE(same(sa, sb));
      // AND the real detections are the same (order aside); only anonymous returns were added
      if (!a.sensors()[i].detections) continue;
      std::vector<agent::Detection> real_a = a.sensors()[i].detections->detections;
      std::vector<agent::Detection> real_b;
      for (const agent::Detection& d : b.sensors()[i].detections->detections) {
        if (d.target_id == agent::kAnonymousId) {
          ++clutter_seen;
        } else {
          real_b.push_back(d);
        }
      }
      const auto by_id = [](const agent::Detection& x, const agent::Detection& y) { return x.target_id < y.target_id; };
      std::sort(real_a.begin(), real_a.end(), by_id);
      std::sort(real_b.begin(), real_b.end(), by_id);
      ASSERT_EQ(real_a.size(), real_b.size());
      for (std::size_t j = 0; j < real_a.size(); ++j) ASSERT_TRUE(same(real_a[j], real_b[j]));
    }
  }
  EXPECT_GT(clutter_seen, 500);  // 6 UAVs x 50 scans x 3 per scan expected = 900
}

}  // namespace
}  // namespace swa::sim
