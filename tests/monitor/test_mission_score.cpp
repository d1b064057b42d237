// A swarm's mission scored against its plan (issue #45): the centroid's end and path errors, the spacing while the
// plan moves, and each UAV's own end error, from synthetic steps.

#include <cmath>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "swa/monitor/mission_score.h"

namespace swa::monitor {
namespace {

using agent::MissionPlan;
using agent::Vec2;

constexpr double kStartS = 10.0;
constexpr double kStepS = 0.5;  // exact in binary, so steps land on the start and the end of the plan

// East 4 s at 1 m/s, then north 2 s at 1 m/s: end point (4, 2) after 6 s.
MissionPlan lPlan() { return MissionPlan({{Vec2(1, 0), 4.0}, {Vec2(0, 1), 2.0}}); }

Geometry geometry(const Vec2& centroid, double d_nb) {
  Geometry g;
  g.centroid_m = centroid;
  g.mean_neighbor_distance_m = d_nb;
  return g;
}

double stepTime(int k) { return kStepS * k; }

TEST(MissionScore, InactiveScoreIgnoresStepsAndGivesNaN) {
  // GIVEN a score without a plan (the run had no mission)
  MissionScore score;
  EXPECT_FALSE(score.active());
  // WHEN steps are added
  for (int k = 0; k < 40; ++k) score.add(stepTime(k), geometry(Vec2(1, 1), 3.0), {{0, Vec2(1, 1)}});
  // THEN there is nothing to report
  const MissionFigures f = score.figures(geometry(Vec2(1, 1), 3.0), {{0, Vec2(1, 1)}});
  EXPECT_TRUE(std::isnan(f.end_error_m));
  EXPECT_TRUE(std::isnan(f.path_error_m));
  EXPECT_TRUE(std::isnan(f.d_nb_moving_m));
  EXPECT_TRUE(std::isnan(f.uav_end_error_m));
  EXPECT_TRUE(std::isnan(f.uav_end_spread_m));
}

TEST(MissionScore, ASwarmOnThePlanScoresZeroAndStepsOutsideThePlanAreIgnored) {
  // GIVEN a plan starting at 10 s, and a swarm wandering far from it before the start, then following it exactly
  // from wherever it was at the start
  const MissionPlan plan = lPlan();
  MissionScore score(plan, kStartS);
  ASSERT_TRUE(score.active());
  const Vec2 origin(50, -20);
  double d_nb_sum = 0.0;
  int moving = 0;
  Geometry last;
  for (int k = 0; k <= 40; ++k) {  // 0 .. 20 s
    const double t = stepTime(k);
    const double tp = t - kStartS;
    Geometry g;
    if (tp < 0.0) {
      g = geometry(Vec2(-300, 700) + Vec2(t, t), 99.0);  // neither the plan's start nor its spacing
    } else if (tp <= plan.duration_s()) {
      g = geometry(origin + plan.pathAt(tp), 4.0 + 0.1 * k);
      d_nb_sum += g.mean_neighbor_distance_m;
      ++moving;
    } else {
      g = geometry(origin + plan.endPoint(), 99.0);  // holding: its spacing is not the moving swarm's
    }
    score.add(t, g, {});
    last = g;
  }
  // WHEN the run is scored
  const MissionFigures f = score.figures(last, {});
  // THEN both errors vanish and d_NB is the mean over the 13 steps from 10 s to 16 s inclusive
  ASSERT_EQ(moving, 13);
  EXPECT_NEAR(f.end_error_m, 0.0, 1e-9);
  EXPECT_NEAR(f.path_error_m, 0.0, 1e-9);
  EXPECT_NEAR(f.d_nb_moving_m, d_nb_sum / moving, 1e-12);
}

// A swarm at `origin` at the start, then `offset` off the plan until its end and `after_end` off it after.
MissionFigures offsetRun(const Vec2& offset, const Vec2& after_end, int* moving) {
  const MissionPlan plan = lPlan();
  MissionScore score(plan, kStartS);
  const Vec2 origin(-7, 3);
  *moving = 0;
  Geometry last;
  for (int k = 0; k <= 40; ++k) {
    const double tp = stepTime(k) - kStartS;
    Vec2 c = origin + plan.pathAt(tp);
    if (tp > plan.duration_s()) {
      c += after_end;
    } else if (tp > 0.0) {
      c += offset;
    }
    if (tp >= 0.0 && tp <= plan.duration_s()) ++*moving;
    last = geometry(c, 5.0);
    score.add(stepTime(k), last, {});
  }
  return score.figures(last, {});
}

TEST(MissionScore, AConstantOffsetAfterTheStartShowsInBothErrors) {
  // GIVEN a swarm that follows the plan (1, 2) m off from the step after the start on: the start centroid is the
  // swarm's position at the first step at/after the start, so an offset already there would be the plan's origin
  int moving = 0;
  const MissionFigures f = offsetRun(Vec2(1, 2), Vec2(1, 2), &moving);
  // THEN the end error is |(1, 2)|, and the path error is that too on every moving step but the first (0 there)
  ASSERT_EQ(moving, 13);
  EXPECT_NEAR(f.end_error_m, std::sqrt(5.0), 1e-9);
  EXPECT_NEAR(f.path_error_m, std::sqrt(5.0) * (moving - 1) / moving, 1e-9);
  EXPECT_NEAR(f.d_nb_moving_m, 5.0, 1e-12);
}

TEST(MissionScore, StepsAfterThePlanEndDecideOnlyTheEndError) {
  // GIVEN the same offset while the plan moves, then a drift to (3, 4) m off once it holds
  int moving = 0;
  const MissionFigures f = offsetRun(Vec2(1, 2), Vec2(3, 4), &moving);
  // THEN the path error does not see the hold, but the end error is the last step's
  EXPECT_NEAR(f.path_error_m, std::sqrt(5.0) * (moving - 1) / moving, 1e-9);
  EXPECT_NEAR(f.end_error_m, 5.0, 1e-9);
}

TEST(MissionScore, EachUavIsScoredFromItsOwnStartPosition) {
  // GIVEN two UAVs 10 m apart at the start (elsewhere before it), and a third that only joins at the end
  const MissionPlan plan = lPlan();
  MissionScore score(plan, kStartS);
  const std::map<int, Vec2> before{{0, Vec2(-100, 0)}, {1, Vec2(100, 0)}};
  const std::map<int, Vec2> at_start{{0, Vec2(0, 0)}, {1, Vec2(10, 0)}};
  score.add(kStartS - kStepS, geometry(Vec2(0, 0), 200.0), before);
  score.add(kStartS, geometry(Vec2(5, 0), 10.0), at_start);
  score.add(kStartS + 3.0, geometry(Vec2(8, 0), 10.0), {{0, Vec2(3, 0)}, {1, Vec2(13, 0)}});
  // WHEN UAV 0 ends exactly on its own planned end and UAV 1 ends 4 m past its own
  const Vec2 end0 = at_start.at(0) + plan.endPoint();
  const Vec2 end1 = at_start.at(1) + plan.endPoint() + Vec2(0, 4);
  const std::map<int, Vec2> at_end{{0, end0}, {1, end1}, {7, Vec2(1000, 1000)}};
  const MissionFigures f = score.figures(geometry(0.5 * (end0 + end1), 10.0), at_end);
  // THEN the mean UAV end error is (0 + 4) / 2, UAV 7 being absent at the start, and the spread is the RMS
  // distance of the two end points to their mean
  EXPECT_NEAR(f.uav_end_error_m, 2.0, 1e-9);
  const Vec2 mean = 0.5 * (end0 + end1);
  const double rms = std::sqrt(0.5 * ((end0 - mean).squaredNorm() + (end1 - mean).squaredNorm()));
  EXPECT_NEAR(f.uav_end_spread_m, rms, 1e-9);
  // AND the centroid, started at (5, 0), ended 2 m off the plan (the mean of the UAVs' offsets)
  EXPECT_NEAR(f.end_error_m, 2.0, 1e-9);
}

TEST(MissionScore, ARunThatNeverReachesTheStartGivesNaN) {
  // GIVEN a plan starting at 10 s and a run that stops at 9.5 s
  MissionScore score(lPlan(), kStartS);
  for (int k = 0; k < 20; ++k) score.add(stepTime(k), geometry(Vec2(0, 0), 4.0), {{0, Vec2(0, 0)}});
  // THEN every figure is NaN: there is no start to measure from
  const MissionFigures f = score.figures(geometry(Vec2(0, 0), 4.0), {{0, Vec2(0, 0)}});
  EXPECT_TRUE(std::isnan(f.end_error_m));
  EXPECT_TRUE(std::isnan(f.path_error_m));
  EXPECT_TRUE(std::isnan(f.d_nb_moving_m));
  EXPECT_TRUE(std::isnan(f.uav_end_error_m));
  EXPECT_TRUE(std::isnan(f.uav_end_spread_m));
}

agent::MissionCommand northFor(double duration_s) {
  agent::MissionCommand c;
  c.legs = {{agent::MissionCommandLeg::Kind::kVelocity, Vec2(0, 1), duration_s, 0.0}};
  return c;
}

TEST(ReplanMission, AChangeMidPlanKeepsThePathUntilThenAndTheStart) {
  // GIVEN the L plan from 10 s, changed at 12 s (2 s into its first leg) to "north for 3 s"
  const ReplannedMission r = replanMission(lPlan().legs(), kStartS, 12.0, northFor(3.0));
  // THEN it still starts at 10 s, runs 2 m east, then 3 m north, and ends there
  EXPECT_EQ(r.start_s, kStartS);
  const MissionPlan plan(r.legs);
  EXPECT_EQ(plan.pathAt(1.0), lPlan().pathAt(1.0));
  EXPECT_EQ(plan.endPoint(), Vec2(2, 3));
  EXPECT_EQ(plan.duration_s(), 5.0);
}

TEST(ReplanMission, ACommandBeforeThePlanOrWithoutOneStartsAMissionThen) {
  for (const std::vector<agent::MissionLeg>& legs : {lPlan().legs(), std::vector<agent::MissionLeg>{}}) {
    const ReplannedMission r = replanMission(legs, kStartS, 4.0, northFor(3.0));
    EXPECT_EQ(r.start_s, 4.0);
    EXPECT_EQ(MissionPlan(r.legs).endPoint(), Vec2(0, 3));
  }
}

TEST(MissionScore, AReplannedMissionIsScoredAgainstTheNewPlanAndKeepsWhatWasScored) {
  // GIVEN a swarm that flies the L plan from 10 s until 12 s, when the ground turns it north for 3 s, and it follows
  MissionScore score(lPlan(), kStartS);
  const ReplannedMission r = replanMission(lPlan().legs(), kStartS, 12.0, northFor(3.0));
  const MissionPlan flown(r.legs);
  Geometry last;
  for (int k = 0; k <= 40; ++k) {
    const double t = stepTime(k);
    if (t == 12.0) score.replan(MissionPlan(r.legs), r.start_s);
    last = geometry(flown.pathAt(t - kStartS), 10.0);
    score.add(t, last, {{0, last.centroid_m}});
  }
  // THEN the swarm is on the plan that was flown: no path error, no end error, each UAV at its end
  const MissionFigures f = score.figures(last, {{0, last.centroid_m}});
  EXPECT_NEAR(f.end_error_m, 0.0, 1e-12);
  EXPECT_NEAR(f.path_error_m, 0.0, 1e-12);
  EXPECT_NEAR(f.uav_end_error_m, 0.0, 1e-12);
  EXPECT_EQ(f.d_nb_moving_m, 10.0);
  // AND against the old plan the same swarm would be (4, 2) - (2, 3) off at the end
  MissionScore old(lPlan(), kStartS);
  for (int k = 0; k <= 40; ++k) {
    const Geometry g = geometry(flown.pathAt(stepTime(k) - kStartS), 10.0);
    old.add(stepTime(k), g, {{0, g.centroid_m}});
  }
  EXPECT_NEAR(old.figures(last, {{0, last.centroid_m}}).end_error_m, (Vec2(4, 2) - Vec2(2, 3)).norm(), 1e-12);
}

}  // namespace
}  // namespace swa::monitor
