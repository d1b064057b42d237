// GNSS: scheduled dropout, kept UAVs, transition events, fix noise.
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "swa/sim/world.h"

namespace swa::sim {
namespace {

using agent::Vec2;

Scenario dropoutScenario(int n, double start_s, double end_s) {
  Scenario s;
  s.uav_count = n;
  s.seed = 9;
  s.dynamics.failsafe_timeout_s = std::numeric_limits<double>::infinity();
  s.gnss.dropout_start_s = start_s;
  s.gnss.dropout_end_s = end_s;
  return s;
}

TEST(WorldGnss, ValidBeforeDropoutInvalidDuringValidAfterAndKeptUavsKeepIt) {
  // GIVEN 3 UAVs losing GNSS over [2 s, 4 s), except UAV 1
  Scenario s = dropoutScenario(3, 2.0, 4.0);
  s.gnss.keep_uavs = {1};
  World world(s);
  std::vector<Event> events(world.events());
  int samples = 0;
  while (world.time_ns() < 6'000'000'000LL) {
    for (std::size_t i = 0; i < 3; ++i) {
      const auto& gnss = world.sensors()[i].gnss;
      if (!gnss) continue;
      ++samples;
      const double t = static_cast<double>(gnss->stamp_ns) * 1e-9;
      const bool expected = i == 1 || t < 2.0 - 1e-9 || t > 4.0 - 1e-9;
      // THEN samples are valid exactly outside the window (or for the kept UAV), and truth agrees
      EXPECT_EQ(gnss->valid, expected) << "uav " << i << " t " << t;
      EXPECT_EQ(world.truth()[i].gnss_valid, expected);
      if (!gnss->valid) {
        EXPECT_EQ(gnss->position_m, Vec2::Zero());
      }
      EXPECT_EQ(gnss->stamp_ns, world.time_ns());
    }
    world.step();
    events.insert(events.end(), world.events().begin(), world.events().end());
  }
  EXPECT_EQ(samples, 3 * 60);  // 10 Hz for 6 s
  // AND each transition is raised once per affected UAV, at the window edges, never for the kept UAV
  ASSERT_EQ(events.size(), 4u);
  EXPECT_EQ(events[0].kind, EventKind::kGnssLost);
  EXPECT_EQ(events[0].uav, 0);
  EXPECT_EQ(events[0].stamp_ns, 2'000'000'000LL);
  EXPECT_EQ(events[1].kind, EventKind::kGnssLost);
  EXPECT_EQ(events[1].uav, 2);
  EXPECT_EQ(events[2].kind, EventKind::kGnssRestored);
  EXPECT_EQ(events[2].uav, 0);
  EXPECT_EQ(events[2].stamp_ns, 4'000'000'000LL);
  EXPECT_EQ(events[3].kind, EventKind::kGnssRestored);
  EXPECT_EQ(events[3].uav, 2);
}

TEST(WorldGnss, LossAtStartIsReportedAtConstruction) {
  // GIVEN the paper's scenario: GNSS lost at t = 0 for all
  const World world(dropoutScenario(4, 0.0, std::numeric_limits<double>::infinity()));
  // THEN construction raises one kGnssLost per UAV at t = 0 and the first fixes are invalid
  ASSERT_EQ(world.events().size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(world.events()[i].kind, EventKind::kGnssLost);
    EXPECT_EQ(world.events()[i].uav, static_cast<int>(i));
    EXPECT_EQ(world.events()[i].stamp_ns, 0);
    EXPECT_FALSE(world.sensors()[i].gnss->valid);
  }
}

TEST(WorldGnss, FixNoiseHasTheConfiguredStd) {
  // GIVEN 4 UAVs that never lose GNSS, std 0.5 m
  Scenario s = dropoutScenario(4, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
  s.gnss.std_m = 0.5;
  World world(s);
  double sum2 = 0.0;
  int n = 0;
  for (int k = 0; k < 20000; ++k) {
    world.step();
    for (std::size_t i = 0; i < 4; ++i) {
      const auto& gnss = world.sensors()[i].gnss;
      if (!gnss) continue;
      ASSERT_TRUE(gnss->valid);
      EXPECT_EQ(gnss->std_m, 0.5);
      sum2 += (gnss->position_m - world.truth()[i].position_m).squaredNorm();
      n += 2;
    }
  }
  std::printf("GNSS error std %.4f m over %d axis samples\n", std::sqrt(sum2 / n), n);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.5, 0.025);
}

}  // namespace
}  // namespace swa::sim
