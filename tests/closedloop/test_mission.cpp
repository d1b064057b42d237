// Issue #45: a swarm that flies a mission without GNSS. Every agent holds the same plan (return_home_8: cruising east
// at 3 m/s, GNSS lost at 10 s, 500 m back west at 4 m/s, a hold) and flies it as a feed-forward under its formation
// control. What must hold of every run is asserted in both builds; the comparison over the seeds with standalone
// UAVs flying the same plan on their own dead reckoning is the Release suite's. The statistics at N = 8 and 16 are in
// BENCHMARKS.md.

#include <gtest/gtest.h>

#include "closed_loop_support.h"

namespace swa::batch {
namespace {

using namespace testing;  // closed_loop_support.h

void expectFlownTogether(const Stats& s) {
  for (const RunResult& r : s.runs) {
    SCOPED_TRACE("seed " + std::to_string(r.seed));
    EXPECT_EQ(r.summary.groups, 1);
    EXPECT_EQ(r.summary.collisions, 0u);
    EXPECT_EQ(r.rejected_inputs, 0u);
  }
}

TEST(ClosedLoopMission, EightUavsFlyHomeTogetherInFormation) {
  // GIVEN the shipped return_home_8
  const Stats s = runSeeds(shipped("return_home_8"));
  // THEN every run keeps one group without a collision, its d_NB within r +- 5 % while moving and +- 3 % at the end
  // (the verdict; measured on seeds 1-10: 9.82-9.90 m and 9.76-10.03 m)
  expectFlownTogether(s);
  for (const RunResult& r : s.runs) {
    EXPECT_NEAR(r.summary.mission_d_nb_moving_m, kR, 0.05 * kR) << "seed " << r.seed;
    EXPECT_NEAR(r.summary.mean_neighbor_distance_m, kR, 0.03 * kR) << "seed " << r.seed;
  }
}

TEST(ClosedLoopMission, TheSwarmEndsNearerItsPlanThanStandaloneUavsEndNearTheirs) {
  // GIVEN the same plan and seeds, flown by the swarm and by standalone UAVs on their own dead reckoning
  const Stats swa = runSeeds(shipped("return_home_8"));
  const Stats standalone = runSeeds(shipped("return_home_8", {"agent.mode=standalone"}));
  // THEN the swarm's centroid ends at most half as far from the plan's end as a standalone UAV ends from its own
  // (the target; measured 4.6 m against 99 m)
  if (kStatistics) {
    EXPECT_LE(swa.mean("mission_end_error_m"), 0.5 * standalone.mean("mission_uav_end_error_m"));
  }
}

TEST(ClosedLoopMission, SixteenUavsWithTwoHundredFortyDegreeSensorsFlyHomeAsOneGroup) {
  // GIVEN 16 UAVs whose sensors see 240 deg: they turn to face the direction of travel, all alike
  const Stats s = runSeeds(shipped("return_home_8", {"uav_count=16", "mps.fov_deg=240"}));
  // THEN every run keeps one group without a collision
  expectFlownTogether(s);
}

}  // namespace
}  // namespace swa::batch
