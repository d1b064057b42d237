// Issue #10's statistics: the Gabriel neighbourhood with the weighted fixed-radius fit and IMU-bias removal (the
// defaults) hold the formation better than the paper's k-nearest rule for every swarm size, and the old rules' known
// failures stay visible as contrasts. 10 seeds per assertion (the issue's tables use 20; BENCHMARKS.md has those, from
// tests/bench/study_formation.cpp); 600 s runs where the issue asks for them.
//
// A benchmark, not a ctest (issue #25: statistics belong to benchmarks): about 3 min of CPU in Release, half an hour
// under the sanitizers. tests/bench/bench_formation_rules.sh runs it; each assertion is a bar of that benchmark. The
// test suite guards every case with one seed and its committed figures (test_formation_guard.cpp).

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

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
  return static_cast<int>(
      std::count_if(s.runs.begin(), s.runs.end(), [](const RunResult& r) { return r.summary.groups > 1; }));
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
  // GIVEN 8 UAVs with a poor IMU (the tilt's bias std 0.15 m/s^2: DESIGN §5's reference; with the accelerometer,
  // the default since issue #44, imu.bias_std changes nothing), 600 s, once with and once without bias removal
  const Stats with = runSeeds(shipped("dropout_8", sized(8, 600.0, {"imu.source=tilt", "imu.bias_std=0.15"})));
  const Stats without = runSeeds(
      shipped("dropout_8", sized(8, 600.0, {"imu.source=tilt", "imu.bias_std=0.15", "agent.focal.bias_window_s=0"})));
  // THEN the centroid moves at most 0.6x as far with it (DESIGN §5 reference: 6.5 m against 12.1 m)
  EXPECT_LE(with.mean("centroid_displacement_m"), 0.6 * without.mean("centroid_displacement_m"));
}

TEST(FormationDrift, BiasRemovalHoldsAPoorAccelerometer) {
  // GIVEN 8 UAVs fusing a poor accelerometer (issue #44's default source): three times the part's bias (0.47 m/s^2
  // per axis) and three times the attitude error (0.015 rad, 0.15 m/s^2 once times g), 600 s, with and without
  // bias removal
  const std::vector<std::string> poor = {"imu.accel_bias_std_mps2=0.47", "imu.attitude_error_std_rad=0.015"};
  std::vector<std::string> off = poor;
  off.push_back("agent.focal.bias_window_s=0");
  const Stats with = runSeeds(shipped("dropout_8", sized(8, 600.0, poor)));
  const Stats without = runSeeds(shipped("dropout_8", sized(8, 600.0, off)));
  // THEN with it the swarm stays one group and its centroid moves at most 0.2x as far as without (measured on seeds
  // 1-10: 9.3 m against 101 m, where the swarm split into up to 3 groups)
  EXPECT_EQ(with.max("groups"), 1.0);
  EXPECT_LE(with.mean("centroid_displacement_m"), 0.2 * without.mean("centroid_displacement_m"));
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
// A limited field of view (issue #26). With constant random headings about one pair in nine is blind to each other,
// and no rule over what a UAV sees keeps such a pair apart (issue #10: 36 collision onsets in 13 of 20 runs at
// 240 deg, N = 8). With heading control every sensor faces the same way, so no pair is: the issue's targets.

struct FieldOfViewCase {
  double fov_deg;
  int n;
  double tolerance;  // d_NB within this fraction of r, at 120 s and at the end
};

class LimitedFieldOfView : public ::testing::TestWithParam<FieldOfViewCase> {};

TEST_P(LimitedFieldOfView, HeadingControlKeepsOneGroupWithoutCollisionAndHoldsTheSpacing) {
  const FieldOfViewCase c = GetParam();
  // GIVEN N UAVs whose sensor sees fov_deg around its axis (the agents told so by the scenario), 10 seeds of 600 s
  const Stats s = runSeeds(shipped("dropout_8", sized(c.n, 600.0, {"mps.fov_deg=" + std::to_string(c.fov_deg)})));
  // THEN no run splits or collides, and d_NB stays within the tolerance of r
  EXPECT_EQ(runsSplit(s), 0);
  EXPECT_EQ(s.max("collisions"), 0.0);
  EXPECT_NEAR(meanAt(s, 120.0), kR, c.tolerance * kR);
  EXPECT_NEAR(s.mean("mean_neighbor_distance_m"), kR, c.tolerance * kR);
}

INSTANTIATE_TEST_SUITE_P(Issue26, LimitedFieldOfView,
                         ::testing::Values(FieldOfViewCase{240.0, 8, 0.03}, FieldOfViewCase{240.0, 16, 0.03},
                                           FieldOfViewCase{180.0, 8, 0.05}),
                         [](const ::testing::TestParamInfo<FieldOfViewCase>& p) {
                           return "Fov" + std::to_string(static_cast<int>(p.param.fov_deg)) + "N" +
                                  std::to_string(p.param.n);
                         });

TEST(LimitedFieldOfViewContrast, ConstantHeadingsStillCollide) {
  // GIVEN the same 240 deg sensors, but agents that believe they see all round (so they keep their random headings)
  const Stats s = runSeeds(shipped("dropout_8", sized(8, 600.0, {"mps.fov_deg=240", "agent.sensor.fov_deg=360"})));
  // THEN mutually blind pairs still collide in some run: heading control, not luck, is what the cases above show
  EXPECT_GT(s.max("collisions"), 0.0);
}

}  // namespace
}  // namespace swa::batch
