// DESIGN §5 / issues #3 and #10: SWA holds the formation after GNSS is lost, standalone UAVs drift apart. The
// targets of the neighbourhood rules over every swarm size are in formation_statistics.cpp (a benchmark). The
// assertions over the seeds are the Release suite's (kStatistics, closed_loop_support.h); the sanitizer stage runs
// two seeds of each case and asserts what holds of every run.

#include <gtest/gtest.h>

#include "closed_loop_support.h"

namespace swa::batch {
namespace {

using namespace testing;  // closed_loop_support.h

void expectCohesive(const Stats& s, double tolerance_fraction, const char* what) {
  SCOPED_TRACE(what);
  // every run: no collision, one group, nothing rejected
  EXPECT_EQ(s.max("collisions"), 0.0);
  EXPECT_EQ(s.max("groups"), 1.0);
  for (const RunResult& r : s.runs) EXPECT_EQ(r.rejected_inputs, 0u) << "seed " << r.seed;
  if (!kStatistics) return;
  // over the seeds: d_NB within the tolerance of r, drift <= 0.08 m/s
  EXPECT_NEAR(s.mean("mean_neighbor_distance_m"), kR, tolerance_fraction * kR);
  EXPECT_LE(s.mean("drift_velocity_mps"), 0.08);
}

TEST(ClosedLoopCohesion, FourUavsHoldFormationWithin3Percent) {
  // GIVEN 4 UAVs (the shipped dropout_4), GNSS lost at 10 s
  // WHEN 10 seeds of 120 s run
  const Stats s = runSeeds(shipped("dropout_4"));
  // THEN d_NB at the end is within 3 % of r, no collision, drift <= 0.08 m/s
  expectCohesive(s, 0.03, "N = 4");
}

TEST(ClosedLoopCohesion, EightUavsHoldFormationWithin3Percent) {
  expectCohesive(runSeeds(shipped("dropout_8")), 0.03, "N = 8");
}

TEST(ClosedLoopCohesion, SixteenUavsHoldFormationWithin3Percent) {
  expectCohesive(runSeeds(shipped("swarm_16")), 0.03, "N = 16");
}

TEST(ClosedLoopCohesion, AnonymousDetectionsWithClutterStayCohesive) {
  // GIVEN LiDAR-like anonymous detections with 0.4 false positives per scan (5 % of 8 detections)
  expectCohesive(runSeeds(shipped("anonymous_8")), 0.03, "anonymous + clutter");
}

TEST(ClosedLoopBaseline, StandaloneUavsDriftApart) {
  // GIVEN the same 8-UAV scenario and seeds, once with SWA and once with the standalone baseline
  const Stats standalone = runSeeds(shipped("dropout_8", {"agent.mode=standalone"}));
  // THEN without SWA the neighbour distance grows to >= 1.3 r
  if (kStatistics) {
    EXPECT_GE(standalone.mean("mean_neighbor_distance_m"), 1.3 * kR);
  }
}

TEST(ClosedLoopBaseline, StandaloneDisplacementIsAtLeastThreeTimesSwa) {
  // GIVEN the same seeds with and without SWA
  const Stats swa = runSeeds(shipped("dropout_8"));
  const Stats standalone = runSeeds(shipped("dropout_8", {"agent.mode=standalone"}));
  // THEN each standalone UAV moves >= 3x as far as a SWA UAV after GNSS loss (measured 22.0 m vs 3.55 m, 6.2x; it
  // was 3.0x with the k = 3 rule before issue #10). The standalone baseline is the paper's dead reckoning: the
  // IMU-bias removal feeds the floating-frame filter only.
  if (kStatistics) {
    EXPECT_GE(standalone.mean("uav_displacement_m"), 3.0 * swa.mean("uav_displacement_m"));
  }
}

TEST(ClosedLoopScaling, DriftFallsAsTheSwarmGrows) {
  // GIVEN independent gusts and IMU biases per UAV
  // WHEN 4 and 16 UAVs fly the same scenario
  const Stats four = runSeeds(shipped("dropout_4"));
  const Stats sixteen = runSeeds(shipped("swarm_16"));
  // THEN the swarm of 16 drifts slower (the paper's headline; disturbances average out over members)
  if (kStatistics) {
    EXPECT_LT(sixteen.mean("drift_velocity_mps"), four.mean("drift_velocity_mps"));
  }
}

TEST(ClosedLoopFit, PapersAlgebraicFitCollapsesTheFormation) {
  // GIVEN the paper's literal method: k = 3 nearest with the algebraic (Kasa) circle fit, where with c free r
  // cancels out of the fit, and no bias removal
  // WHEN 8 UAVs fly
  // (kNearest's unweighted fixed-radius setting would be refused: the algebraic fit has no neighbour weights)
  const Stats s = runSeeds(shipped("dropout_8", {"agent.formation.neighbourhood=k_nearest", "agent.formation.k=3",
                                                 "agent.focal.bias_window_s=0", "agent.circle_fit=algebraic"}));
  // THEN they collapse onto each other, which is why fixed_radius is the default
  if (kStatistics) {
    EXPECT_LT(s.mean("mean_neighbor_distance_m"), 0.3 * kR);
    EXPECT_GT(s.mean("collisions"), 0.0);
  }
}

TEST(ClosedLoopAnchored, OneUavKeepingGnssStopsTheSwarmDrifting) {
  // GIVEN anchored agents and UAV 0 keeping GNSS while the others lose it at 10 s (400 s, see the scenario file)
  const Stats s = runSeeds(shipped("anchored_8"));
  // THEN the centroid's net drift is <= 0.01 m/s and the formation still holds
  if (kStatistics) {
    EXPECT_LE(s.mean("drift_velocity_mps"), 0.01);
  }
  expectCohesive(s, 0.03, "anchored");
}

TEST(ClosedLoopConsistency, FocalAneesInsideTheChi2BandOnTheDefaultScenario) {
  // GIVEN the default scenario; ANEES is averaged over the 8 agents (K = 8, n = 2) and over time after GNSS loss
  const Stats s = runSeeds(shipped("dropout_8"));
  for (const RunResult& r : s.runs) {
    SCOPED_TRACE(r.seed);
    // THEN each seed's ANEES of position lies in its 95 % band
    EXPECT_GE(r.summary.anees_position, r.summary.anees_band_low);
    EXPECT_LE(r.summary.anees_position, r.summary.anees_band_high);
  }
  // AND at least 80 % of the steps are inside the band, averaged over the seeds (issue #10; R_c and Q_f were tuned
  // on seeds 101-120, these are 1-10; measured ANEES 2.33, 86 % of steps). Before: 3.4 with 60 %.
  if (kStatistics) {
    EXPECT_GE(s.mean("anees_position_in_band"), 0.80);
  }
}

}  // namespace
}  // namespace swa::batch
