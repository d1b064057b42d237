// The run verdict and its exit status: PASS only when the scenario completed with d_NB within the band, no
// collision, one group and no UAV on failsafe at the end; FAIL lists every failed criterion; INCOMPLETE wins whenever
// the run did not complete.

#include <gtest/gtest.h>

#include <string>

#include "monitor_options.h"
#include "swa/run_record/scoring.h"
#include "swa/run_record/verdict.h"
#include "verdict_input.h"

namespace swa::record {
namespace {

VerdictInput good() { return testing::passingRun(); }

bool mentions(const Verdict& v, const std::string& what) {
  for (const std::string& r : v.reasons) {
    if (r.find(what) != std::string::npos) return true;
  }
  return false;
}

TEST(MonitorVerdict, PassNeedsEveryCriterion) {
  // WHEN a completed run with d_NB within the band, no collision and one group is judged
  const Verdict v = judge(good());
  // THEN it passes, for no reason, and exits 0
  EXPECT_EQ(v.outcome, Outcome::kPass);
  EXPECT_TRUE(v.reasons.empty());
  EXPECT_EQ(verdictText(v), "PASS");
  EXPECT_EQ(exitCode(v.outcome), 0);
}

TEST(MonitorVerdict, UavsOnFailsafeAtTheEndFailTheRunWhateverTheFormation) {
  // GIVEN a run that held the formation but ended with the agents of UAVs 1 and 5 dead (their UAVs hovering)
  VerdictInput in = good();
  in.failsafe_at_end = {1, 5};
  // THEN it fails, naming them
  const Verdict v = judge(in);
  EXPECT_EQ(v.outcome, Outcome::kFail);
  EXPECT_EQ(verdictText(v), "FAIL: UAVs 1, 5 on failsafe at the end (agent declared dead, never rejoined)");
  EXPECT_EQ(exitCode(v.outcome), 1);
  // AND a run the monitor did not see whole stays INCOMPLETE, with the failsafe among its reasons
  in.missed = {{10.0, 12.0}};
  EXPECT_EQ(judge(in).outcome, Outcome::kIncomplete);
  EXPECT_TRUE(mentions(judge(in), "on failsafe"));
}

TEST(MonitorVerdict, AFailInAWindTheTiltCannotReadSaysWhy) {
  // GIVEN the scoring of a tilt-reading swarm in an 8 m/s wind, and of the same swarm reading its accelerometer
  sim::Scenario s;
  s.wind.mean_mps = 8.0;
  s.agent.focal.imu_source = agent::ImuSource::kTilt;
  const Scoring tilt = scoringOf(s);
  s.agent.focal.imu_source = agent::ImuSource::kAccelerometer;
  EXPECT_TRUE(scoringOf(s).failure_hint.empty());
  s.wind.mean_mps = 0.0;
  s.agent.focal.imu_source = agent::ImuSource::kTilt;
  EXPECT_TRUE(scoringOf(s).failure_hint.empty());  // calm air: nothing to blame on the wind
  // WHEN the tilt swarm's run split
  VerdictInput in = good();
  in.failure_hint = tilt.failure_hint;
  in.summary.groups = 3;
  const Verdict v = judge(in);
  // THEN the verdict names the split, and last why: the tilt takes the lean into the wind for acceleration
  EXPECT_EQ(v.outcome, Outcome::kFail);
  ASSERT_EQ(v.reasons.size(), 2u);
  EXPECT_EQ(v.reasons[0], "3 groups at the end (expected 1)");
  EXPECT_NE(v.reasons[1].find("likely because the agents read their acceleration from the tilt (imu.source tilt) in "
                              "a mean wind of 8 m/s"),
            std::string::npos)
      << v.reasons[1];
  // AND a run that passed says nothing of it
  in.summary.groups = 1;
  EXPECT_EQ(verdictText(judge(in)), "PASS");
}

TEST(MonitorVerdict, BandEdgesAreInclusive) {
  // GIVEN a passing run with r = 10 m and a 10 % band
  VerdictInput in = good();
  // WHEN d_NB is exactly 9 m or 11 m THEN it passes
  in.summary.mean_neighbor_distance_m = 9.0;
  EXPECT_EQ(judge(in).outcome, Outcome::kPass);
  in.summary.mean_neighbor_distance_m = 11.0;
  EXPECT_EQ(judge(in).outcome, Outcome::kPass);
  // WHEN d_NB is just outside, 11.01 m or 8.99 m, THEN it fails
  in.summary.mean_neighbor_distance_m = 11.01;
  EXPECT_EQ(judge(in).outcome, Outcome::kFail);
  in.summary.mean_neighbor_distance_m = 8.99;
  EXPECT_EQ(judge(in).outcome, Outcome::kFail);
  // WHEN the band is widened to 20 % THEN 8.99 m passes
  in.scoring.radius_tolerance = 0.2;  // a wider band accepts it
  EXPECT_EQ(judge(in).outcome, Outcome::kPass);
}

TEST(MonitorVerdict, DefaultBandIsFivePercentOfR) {
  // GIVEN the default tolerance (issue #10 tightened it from 10 %: the Gabriel rule holds d_NB within 3 %)
  VerdictInput in = good();
  in.scoring.radius_tolerance = VerdictInput{}.scoring.radius_tolerance;
  EXPECT_DOUBLE_EQ(in.scoring.radius_tolerance, 0.05);
  // THEN 9.5 and 10.5 m pass, 9.4 and 10.6 m (which the old band passed) fail
  for (double d : {9.5, 10.5}) {
    in.summary.mean_neighbor_distance_m = d;
    EXPECT_EQ(judge(in).outcome, Outcome::kPass) << d;
  }
  for (double d : {9.4, 10.6}) {
    in.summary.mean_neighbor_distance_m = d;
    EXPECT_EQ(judge(in).outcome, Outcome::kFail) << d;
  }
}

TEST(MonitorVerdict, EachFailureIsNamed) {
  // GIVEN a passing run
  VerdictInput in = good();
  // WHEN d_NB is outside the band THEN it fails, naming d_NB and r, and exits 1
  in.summary.mean_neighbor_distance_m = 12.0;
  Verdict v = judge(in);
  EXPECT_EQ(v.outcome, Outcome::kFail);
  EXPECT_TRUE(mentions(v, "final d_NB 12 m outside r = 10 m"));
  EXPECT_EQ(exitCode(v.outcome), 1);

  // WHEN there are collisions THEN it fails, naming them
  in = good();
  in.summary.collisions = 2;
  v = judge(in);
  EXPECT_EQ(v.outcome, Outcome::kFail);
  EXPECT_TRUE(mentions(v, "2 collision(s)"));

  // WHEN the swarm ends in 3 groups THEN that is named
  in = good();
  in.summary.groups = 3;
  v = judge(in);
  EXPECT_TRUE(mentions(v, "3 groups at the end"));

  // WHEN nobody is present at the end (0 groups, d_NB undefined) THEN it fails, naming both
  in = good();
  in.summary.groups = 0;  // nobody present at the end
  in.summary.mean_neighbor_distance_m = monitor::kNaN;
  v = judge(in);
  EXPECT_EQ(v.outcome, Outcome::kFail);
  EXPECT_TRUE(mentions(v, "final d_NB undefined"));
  EXPECT_TRUE(mentions(v, "0 groups"));
}

TEST(MonitorVerdict, AllFailuresListedTogether) {
  // GIVEN a run with d_NB far outside the band, a collision and 2 groups
  VerdictInput in = good();
  in.summary.mean_neighbor_distance_m = 3.0;
  in.summary.collisions = 1;
  in.summary.groups = 2;
  // WHEN it is judged THEN all three reasons are listed, d_NB first
  const Verdict v = judge(in);
  EXPECT_EQ(v.reasons.size(), 3u);
  EXPECT_EQ(verdictText(v).rfind("FAIL: final d_NB", 0), 0u);
}

TEST(MonitorVerdict, NotCompletedIsIncompleteEvenIfTheNumbersAreGood) {
  // GIVEN a run with good numbers that was interrupted
  VerdictInput in = good();
  in.completed = false;
  in.end_reason = "interrupted by SIGINT";
  // WHEN it is judged THEN it is INCOMPLETE, saying why, and exits 3
  const Verdict v = judge(in);
  EXPECT_EQ(v.outcome, Outcome::kIncomplete);
  EXPECT_TRUE(mentions(v, "scenario not completed: interrupted by SIGINT"));
  EXPECT_EQ(exitCode(v.outcome), 3);
}

TEST(MonitorVerdict, IncompleteWinsOverFailAndKeepsTheFailures) {
  // GIVEN a run that did not complete (discovery timeout) and had a collision
  VerdictInput in = good();
  in.completed = false;
  in.end_reason = "simulator ended the scenario: discovery timeout";
  in.summary.collisions = 1;
  // WHEN it is judged THEN it is INCOMPLETE, naming both the end and the collision
  const Verdict v = judge(in);
  EXPECT_EQ(v.outcome, Outcome::kIncomplete);
  EXPECT_TRUE(mentions(v, "discovery timeout"));
  EXPECT_TRUE(mentions(v, "1 collision(s)"));
}

TEST(MonitorVerdict, NoTruthIsIncompleteEvenWhenTheSimulatorCompleted) {
  // GIVEN a run that completed but whose monitor received no ground truth
  VerdictInput in = good();
  in.saw_truth = false;
  // WHEN it is judged THEN it is INCOMPLETE, saying so
  Verdict v = judge(in);
  EXPECT_EQ(v.outcome, Outcome::kIncomplete);
  EXPECT_TRUE(mentions(v, "no ground truth received"));
  // WHEN the monitor also timed out waiting for the end THEN the reason names --timeout-s
  in.completed = false;
  in.end_reason = "no EVENT_SCENARIO_END within 5 s (--timeout-s)";
  v = judge(in);
  EXPECT_TRUE(mentions(v, "--timeout-s"));
}

TEST(MonitorVerdict, NamesRoundTripAndExitCodesMatchTheOptions) {
  // WHEN each outcome's name is parsed back THEN it is that outcome
  for (const Outcome o : {Outcome::kPass, Outcome::kFail, Outcome::kIncomplete}) {
    ASSERT_TRUE(parseOutcome(toString(o)).has_value());
    EXPECT_EQ(*parseOutcome(toString(o)), o);
  }
  // AND names are exact: "pass" is not an outcome
  EXPECT_FALSE(parseOutcome("pass").has_value());
  // AND the exit statuses are those of swa_monitor's options, bad input being 2
  EXPECT_EQ(exitCode(Outcome::kPass), monitor_node::kExitPass);
  EXPECT_EQ(exitCode(Outcome::kFail), monitor_node::kExitFail);
  EXPECT_EQ(exitCode(Outcome::kIncomplete), monitor_node::kExitIncomplete);
  EXPECT_EQ(monitor_node::kExitBadInput, 2);
}

}  // namespace
}  // namespace swa::record
