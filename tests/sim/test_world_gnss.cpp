// GNSS: scheduled dropout, kept UAVs, per-UAV windows, transition events, fix noise.
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>
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

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr agent::StampNs kNs = 1'000'000'000LL;

// Per UAV, the [start_ns, end_ns) intervals in which it has no GNSS.
using Outages = std::vector<std::vector<std::pair<agent::StampNs, agent::StampNs>>>;

// Runs `world` to `end_ns`, checking truth.gnss_valid (and every GNSS sample) against `outages` on every step;
// returns every event raised, construction included.
std::vector<Event> runAndCheckOutages(World& world, agent::StampNs end_ns, const Outages& outages) {
  std::vector<Event> events(world.events());
  for (;;) {
    const agent::StampNs t = world.time_ns();
    for (std::size_t i = 0; i < outages.size(); ++i) {
      bool expected = true;
      for (const auto& [start, end] : outages[i]) {
        if (t >= start && t < end) expected = false;
      }
      EXPECT_EQ(world.truth()[i].gnss_valid, expected) << "uav " << i << " t " << t;
      if (const auto& gnss = world.sensors()[i].gnss) {
        EXPECT_EQ(gnss->valid, expected) << "uav " << i << " t " << t;
      }
    }
    if (t >= end_ns) break;
    world.step();
    events.insert(events.end(), world.events().begin(), world.events().end());
  }
  return events;
}

struct GnssEvent {
  agent::StampNs stamp_ns;
  EventKind kind;
  int uav;
};

void expectGnssEvents(const std::vector<Event>& events, const std::vector<GnssEvent>& expected) {
  ASSERT_EQ(events.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(events[i].stamp_ns, expected[i].stamp_ns) << "event " << i;
    EXPECT_EQ(events[i].kind, expected[i].kind) << "event " << i;
    EXPECT_EQ(events[i].uav, expected[i].uav) << "event " << i;
  }
}

TEST(WorldGnss, GivenAUavWithItsOwnWindow_ThenOnlyItLosesAndRegainsGnssExactlyAtTheEdges) {
  // GIVEN 3 UAVs with no common dropout, and UAV 1 without GNSS over [1.25 s, 3.7 s)
  Scenario s = dropoutScenario(3, kInf, kInf);
  s.gnss.windows = {{1, 1.25, 3.7}};
  World world(s);
  // WHEN it runs for 5 s
  const std::vector<Event> events = runAndCheckOutages(world, 5 * kNs, {{}, {{1'250'000'000LL, 3'700'000'000LL}}, {}});
  // THEN UAV 1 raises one loss and one restoration, at the window's edges, and the others raise nothing
  expectGnssEvents(events,
                   {{1'250'000'000LL, EventKind::kGnssLost, 1}, {3'700'000'000LL, EventKind::kGnssRestored, 1}});
}

TEST(WorldGnss, GivenOwnWindowsAndTheCommonWindow_ThenAUavIsWithoutGnssInTheirUnion) {
  // GIVEN a common dropout over [2 s, 4 s) that UAV 3 is kept out of, and own windows:
  Scenario s = dropoutScenario(5, 2.0, 4.0);
  s.gnss.keep_uavs = {3};
  s.gnss.windows = {
      {0, 3.0, 6.0},   // overlaps the end of the common window
      {1, 1.0, 2.0},   // ends exactly where the common window starts
      {2, 5.0, kInf},  // after the common window, never restored
      {3, 2.5, 3.0},   // kept UAV: keep_uavs does not exempt it from its own window
      {4, 0.5, 1.5},   // two overlapping windows of one UAV
      {4, 1.0, 1.8},
  };
  World world(s);
  // WHEN it runs for 7 s
  const std::vector<Event> events = runAndCheckOutages(world, 7 * kNs,
                                                       {{{2 * kNs, 6 * kNs}},
                                                        {{1 * kNs, 4 * kNs}},
                                                        {{2 * kNs, 4 * kNs}, {5 * kNs, 100 * kNs}},
                                                        {{2'500'000'000LL, 3 * kNs}},
                                                        {{500'000'000LL, 1'800'000'000LL}, {2 * kNs, 4 * kNs}}});
  // THEN GNSS is missing exactly in the union of each UAV's windows, with one event per edge of that union (none
  // where two windows meet or overlap), in UAV order within a step
  expectGnssEvents(events, {
                               {500'000'000LL, EventKind::kGnssLost, 4},
                               {1 * kNs, EventKind::kGnssLost, 1},
                               {1'800'000'000LL, EventKind::kGnssRestored, 4},
                               {2 * kNs, EventKind::kGnssLost, 0},
                               {2 * kNs, EventKind::kGnssLost, 2},
                               {2 * kNs, EventKind::kGnssLost, 4},
                               {2'500'000'000LL, EventKind::kGnssLost, 3},
                               {3 * kNs, EventKind::kGnssRestored, 3},
                               {4 * kNs, EventKind::kGnssRestored, 1},
                               {4 * kNs, EventKind::kGnssRestored, 2},
                               {4 * kNs, EventKind::kGnssRestored, 4},
                               {5 * kNs, EventKind::kGnssLost, 2},
                               {6 * kNs, EventKind::kGnssRestored, 0},
                           });
}

TEST(WorldGnss, GivenAnOwnWindowFromTimeZero_ThenTheLossIsReportedAtConstruction) {
  // GIVEN no common dropout and UAV 2 of 3 without GNSS from t = 0, never restored
  Scenario s = dropoutScenario(3, kInf, kInf);
  s.gnss.windows = {{2, 0.0, kInf}};
  const World world(s);
  // THEN construction raises exactly its loss, and only its first fix is invalid
  expectGnssEvents(world.events(), {{0, EventKind::kGnssLost, 2}});
  EXPECT_TRUE(world.sensors()[0].gnss->valid);
  EXPECT_TRUE(world.sensors()[1].gnss->valid);
  EXPECT_FALSE(world.sensors()[2].gnss->valid);
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
