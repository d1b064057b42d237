// Issue #10's statistics: the Gabriel neighbourhood with the weighted fixed-radius fit and IMU-bias removal (the
// defaults) hold the formation better than the paper's k-nearest rule for every swarm size, and the old rules' known
// failures stay visible as contrasts. 10 seeds per assertion (the tables use 20; BENCHMARKS.md has those, from
// tests/bench/study_formation.cpp); 600 s runs where the issue asks for them.
//
// A benchmark, not a ctest (issue #25: statistics belong to benchmarks): about 3 min of CPU in Release, half an hour
// under the sanitizers. tests/bench/bench_formation_rules.sh runs it; each assertion is a bar of that benchmark. The
// test suite guards every case with one seed and its committed figures (test_formation_guard.cpp).

#include <algorithm>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "closed_loop_support.h"

namespace swa::batch {
namespace {

using namespace testing;  // closed_loop_support.h

std::vector<std::string> sized(int n, double duration_s, std::vector<std::string> more = {}) {
  more.insert(more.begin(), {"uav_count=" + std::to_string(n), "duration_s=" + std::to_string(duration_s)});
  return more;
}

double meanAt(const Stats& s, double t_s) {
  double sum = 0.0;
  for (const RunResult& r : s.runs) sum += meanNeighbourDistanceAt(r, t_s);
  return sum / static_cast<double>(s.runs.size());
}

int runsSplit(const Stats& s) {
  return static_cast<int>(std::count_if(s.runs.begin(), s.runs.end(), [](const RunResult& r) {
    return r.summary.groups > 1;
  }));
}

// ---------------------------------------------------------------------------------------------------------------
// Every swarm size from 3 to 16, 600 s: spacing within 3 % at 120 s and at the end, one group, no collision.

class EverySwarmSize : public ::testing::TestWithParam<int> {};

TEST_P(EverySwarmSize, GabrielHoldsSpacingWithinThreePercentInOneGroupWithoutCollision) {
  const int n = GetParam();
  // GIVEN N UAVs of the default scenario (GNSS lost at 10 s) with the default rules, 10 seeds of 600 s
  const Stats s = runSeeds(shipped("dropout_8", sized(n, 600.0)));
  // THEN d_NB (mean over the seeds) is within 3 % of r at 120 s and at 600 s
  EXPECT_NEAR(meanAt(s, 120.0), kR, 0.03 * kR);
  EXPECT_NEAR(s.mean("mean_neighbor_distance_m"), kR, 0.03 * kR);
  // AND every run ends as one group, without a collision, nobody ever closer than 7 m
  EXPECT_EQ(runsSplit(s), 0);
  EXPECT_EQ(s.max("collisions"), 0.0);
  EXPECT_GE(s.min("min_separation_m"), 7.0);
  // AND the true Gabriel edges average r within 3 % too (d_NB's two nearest read low for UAVs with 3-6 neighbours)
  EXPECT_NEAR(s.mean("edge_length_m"), kR, 0.03 * kR);
}

INSTANTIATE_TEST_SUITE_P(ThreeToSixteen, EverySwarmSize, ::testing::Range(3, 17),
                         [](const ::testing::TestParamInfo<int>& param) { return "N" + std::to_string(param.param); });

// ---------------------------------------------------------------------------------------------------------------
// Drift and IMU-bias removal.

TEST(FormationDrift, EightUavsDriftAtMostFortyFiveMillimetresPerSecond) {
  // GIVEN 8 UAVs, IMU bias std 0.05 m/s^2 (the default), 600 s
  const Stats s = runSeeds(shipped("dropout_8", sized(8, 600.0)));
  // THEN the centroid speed, averaged over consecutive 60 s windows, is <= 0.045 m/s (k = 3 nearest: 0.057-0.067)
  EXPECT_LE(s.mean("drift_velocity_windows_mps"), 0.045);
}

TEST(FormationDrift, BiasRemovalCutsTheDisplacementOfAPoorImuBelowSixTenths) {
  // GIVEN 8 UAVs with a poor IMU (bias std 0.15 m/s^2), 600 s, once with and once without bias removal
  const Stats with = runSeeds(shipped("dropout_8", sized(8, 600.0, {"imu.bias_std=0.15"})));
  const Stats without =
      runSeeds(shipped("dropout_8", sized(8, 600.0, {"imu.bias_std=0.15", "agent.focal.bias_window_s=0"})));
  // THEN the centroid moves at most 0.6x as far with it (DESIGN §5 reference: 6.5 m against 12.1 m)
  EXPECT_LE(with.mean("centroid_displacement_m"), 0.6 * without.mean("centroid_displacement_m"));
}

// ---------------------------------------------------------------------------------------------------------------
// The old rules' known behaviour, as contrasts.

TEST(OldRules, ThreeNearestSqueezeTheFormation) {
  // GIVEN k = 3 nearest with the unweighted fit: a second-shell UAV at sqrt(3) r is often the third neighbour and is
  // pulled to r
  const Stats eight = runSeeds(shipped("dropout_8", kNearest(3)));
  const Stats four = runSeeds(shipped("dropout_4", kNearest(3)));
  // THEN the formation settles short of r: ~0.93 r at N = 8, ~0.855 r at N = 4 (where four points cannot all be r
  // apart), while it stays one group
  EXPECT_LT(eight.mean("mean_neighbor_distance_m"), 0.95 * kR);
  EXPECT_LT(four.mean("mean_neighbor_distance_m"), 0.90 * kR);
  EXPECT_EQ(eight.max("groups"), 1.0);
}

TEST(OldRules, TwoNearestKeepTheSpacingButSplit) {
  // GIVEN k = 2 nearest, 8 UAVs, 600 s
  const Stats s = runSeeds(shipped("dropout_8", sized(8, 600.0, kNearest(2))));
  // THEN the spacing is right (within 3 %) but some runs end in more than one group (DESIGN §5: 6/20)
  EXPECT_NEAR(s.mean("mean_neighbor_distance_m"), kR, 0.03 * kR);
  EXPECT_GE(runsSplit(s), 1);
}

// ---------------------------------------------------------------------------------------------------------------
// A limited field of view. The target (240 deg, N = 8, 600 s: one group, no collision, d_NB within 5 %) is
// NOT met: every collision left is between two UAVs that are each in the other's blind sector (19 of 19 over these
// seeds), which no rule over what a UAV sees can keep apart; see BENCHMARKS.md "Limited field of view" for the
// variants tried. What the defaults do achieve over the old rule is asserted here, so a regression shows.

TEST(LimitedFieldOfView, GabrielHalvesTheCollisionsAndTheDriftOfThreeNearest) {
  // GIVEN 8 UAVs whose sensor sees 240 deg around its heading (headings random), 600 s, at Table I's k_p = 0.5,
  // the gain this comparison of the rules was measured at. With the default k_p = 0.7 Gabriel collides more under
  // a limited field of view (20 seeds: 63 onsets in 17 runs against 36 in 13; k3 77 against 79; BENCHMARKS.md,
  // issue #24): the faster position loop closes on blind neighbours sooner. Issue #26 (heading control) owns that.
  const std::vector<std::string> fov = {"mps.fov_deg=240", "agent.control.k_p=0.5"};
  const Stats gabriel = runSeeds(shipped("dropout_8", sized(8, 600.0, fov)));
  const Stats k3 = runSeeds(shipped("dropout_8", sized(8, 600.0, kNearest(3, fov))));
  double collisions_gabriel = 0.0, collisions_k3 = 0.0;
  for (const RunResult& r : gabriel.runs) collisions_gabriel += static_cast<double>(r.summary.collisions);
  for (const RunResult& r : k3.runs) collisions_k3 += static_cast<double>(r.summary.collisions);
  // THEN the defaults collide at most 0.6x as often as k = 3 nearest (measured 19 against 38 collision onsets) ...
  EXPECT_LE(collisions_gabriel, 0.6 * collisions_k3);
  // ... drift at most half as fast (0.062 against 0.195 m/s, 60 s windows) ...
  EXPECT_LE(gabriel.mean("drift_velocity_windows_mps"), 0.5 * k3.mean("drift_velocity_windows_mps"));
  // ... and keep d_NB within 5 % of r on average (10.36 m, against 8.81 m for k = 3)
  EXPECT_NEAR(gabriel.mean("mean_neighbor_distance_m"), kR, 0.05 * kR);
}

}  // namespace
}  // namespace swa::batch
