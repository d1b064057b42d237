// The truth/state join of swa_monitor (StepJoiner): when a step is complete, what waits and for how long, and
// every kind of bad or badly timed input being dropped and counted rather than crashing or scoring garbage.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "step_joiner.h"

namespace swa::monitor_node {
namespace {

constexpr agent::StampNs kStep = 100'000'000;  // 100 ms

// Truth of `n` UAVs (ids 0..n-1) at step k; `dead` lists UAVs whose agent is not alive.
TruthSample truth(int k, int n, std::vector<int> dead = {}) {
  TruthSample t;
  t.stamp_ns = k * kStep;
  for (int i = 0; i < n; ++i) {
    monitor::UavTruth u;
    u.id = i;
    u.position_m = agent::Vec2(10.0 * i, 0.0);
    t.uavs.push_back(u);
    t.agent_alive.push_back(std::find(dead.begin(), dead.end(), i) == dead.end());
  }
  return t;
}

StateSample state(int uav, agent::StampNs stamp_ns, double x = 0.0) {
  StateSample s;
  s.uav = uav;
  s.stamp_ns = stamp_ns;
  s.estimate.valid = true;
  s.estimate.position_m = agent::Vec2(x, 0.0);
  return s;
}

void allStates(StepJoiner& j, int k, int n) {
  for (int i = 0; i < n; ++i) j.addState(state(i, k * kStep));
}

TEST(StepJoiner, StepCompleteOnceEveryLiveAgentReported) {
  StepJoiner j;
  j.addTruth(truth(0, 3));
  j.addState(state(2, 0));
  j.addState(state(0, 0));
  EXPECT_TRUE(j.takeReady().empty());
  EXPECT_FALSE(j.idle());
  j.addState(state(1, 0));
  const std::vector<JoinedStep> ready = j.takeReady();
  ASSERT_EQ(ready.size(), 1u);
  ASSERT_EQ(ready[0].states.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(ready[0].states[static_cast<std::size_t>(i)].has_value());
    EXPECT_EQ(ready[0].states[static_cast<std::size_t>(i)]->uav, i);  // in the truth's order, not arrival order
  }
  EXPECT_TRUE(j.idle());
  EXPECT_EQ(j.counters().steps_incomplete, 0u);
  EXPECT_EQ(j.counters().missing_states, 0u);
}

TEST(StepJoiner, DeadAgentsAreNotWaitedFor) {
  StepJoiner j;
  j.addTruth(truth(0, 3, {1}));
  j.addState(state(0, 0));
  j.addState(state(2, 0));
  const std::vector<JoinedStep> ready = j.takeReady();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_FALSE(ready[0].states[1].has_value());
  EXPECT_EQ(j.counters().missing_states, 0u);  // a dead agent's state is not missing
}

TEST(StepJoiner, DeadAgentsStateIsStillUsedWhenItComes) {
  StepJoiner j;
  j.addState(state(1, 0, 4.0));  // the stalled agent still reports, before the truth
  j.addTruth(truth(0, 2, {1}));
  j.addState(state(0, 0));
  const std::vector<JoinedStep> ready = j.takeReady();
  ASSERT_EQ(ready.size(), 1u);
  ASSERT_TRUE(ready[0].states[1].has_value());
  EXPECT_DOUBLE_EQ(ready[0].states[1]->estimate.position_m.x(), 4.0);
}

TEST(StepJoiner, StatesBeforeTheirTruthAreHeld) {
  StepJoiner j;
  allStates(j, 0, 2);
  EXPECT_TRUE(j.takeReady().empty());
  j.addTruth(truth(0, 2));
  EXPECT_EQ(j.takeReady().size(), 1u);
  EXPECT_EQ(j.counters().state_unmatched, 0u);
}

TEST(StepJoiner, MissingStateReleasedAfterHorizonInOrder) {
  StepJoiner j(5);
  j.addTruth(truth(0, 2));
  j.addState(state(0, 0));  // UAV 1 never reports for step 0
  for (int k = 1; k <= 4; ++k) {
    j.addTruth(truth(k, 2));
    allStates(j, k, 2);
    // Steps 1..4 are complete, but nothing overtakes step 0.
    EXPECT_TRUE(j.takeReady().empty()) << k;
  }
  j.addTruth(truth(5, 2));  // the 5th newer truth sample: step 0 goes, and the complete ones behind it
  const std::vector<JoinedStep> ready = j.takeReady();
  ASSERT_EQ(ready.size(), 5u);
  for (std::size_t k = 0; k < ready.size(); ++k)
    EXPECT_EQ(ready[k].truth.stamp_ns, static_cast<agent::StampNs>(k) * kStep);
  EXPECT_TRUE(ready[0].states[0].has_value());
  EXPECT_FALSE(ready[0].states[1].has_value());
  EXPECT_EQ(j.counters().steps_incomplete, 1u);
  EXPECT_EQ(j.counters().missing_states, 1u);
  EXPECT_FALSE(j.idle());  // step 5 still waits
}

TEST(StepJoiner, LateStateAfterReleaseIsDroppedAndCounted) {
  StepJoiner j(1);
  j.addTruth(truth(0, 2));
  j.addState(state(0, 0));
  j.addTruth(truth(1, 2));  // horizon 1: step 0 released without UAV 1
  ASSERT_EQ(j.takeReady().size(), 1u);
  j.addState(state(1, 0));
  EXPECT_EQ(j.counters().state_late, 1u);
  EXPECT_EQ(j.counters().state_unmatched, 0u);
}

TEST(StepJoiner, DuplicateStateFirstOneWins) {
  StepJoiner j;
  j.addTruth(truth(0, 2));
  j.addState(state(0, 0, 1.0));
  j.addState(state(0, 0, 2.0));
  j.addState(state(1, 0));
  const std::vector<JoinedStep> ready = j.takeReady();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_DOUBLE_EQ(ready[0].states[0]->estimate.position_m.x(), 1.0);
  EXPECT_EQ(j.counters().state_duplicate, 1u);
  // A duplicate that was held before its truth arrived counts the same.
  j.addState(state(0, kStep));
  j.addState(state(0, kStep));
  j.addTruth(truth(1, 2));
  EXPECT_EQ(j.counters().state_duplicate, 2u);
}

TEST(StepJoiner, StateOfUnknownUavIsDropped) {
  StepJoiner j;
  j.addState(state(9, 0));  // held, then found not to be in the truth
  j.addTruth(truth(0, 2));
  j.addState(state(-1, 0));  // pending step, unknown id
  EXPECT_EQ(j.counters().state_unknown_uav, 2u);
  allStates(j, 0, 2);
  EXPECT_EQ(j.takeReady().size(), 1u);
}

TEST(StepJoiner, StatesForStampsNeverSeenAreUnmatched) {
  StepJoiner j;
  j.addTruth(truth(1, 1));
  j.addState(state(0, kStep / 2));          // older than the newest truth, no truth with that stamp: at once
  j.addState(state(0, kStep + kStep / 2));  // newer: held ...
  EXPECT_EQ(j.counters().state_unmatched, 1u);
  j.addTruth(truth(2, 1));  // ... until a newer truth shows its stamp will never come
  EXPECT_EQ(j.counters().state_unmatched, 2u);
  j.addState(state(0, 3 * kStep));                 // held
  const std::vector<JoinedStep> rest = j.flush();  // the end: held states are unmatched
  EXPECT_EQ(rest.size(), 2u);
  EXPECT_EQ(j.counters().state_unmatched, 3u);
  EXPECT_TRUE(j.idle());
}

TEST(StepJoiner, HeldStatesAreBounded) {
  StepJoiner j;
  const std::size_t extra = 10;
  for (std::size_t k = 0; k < StepJoiner::kMaxEarlyStates + extra; ++k) {
    j.addState(state(0, static_cast<agent::StampNs>(k + 1) * kStep));
  }
  EXPECT_EQ(j.counters().state_unmatched, extra);     // the oldest gave way
  j.addTruth(truth(static_cast<int>(extra) + 1, 1));  // the oldest held stamp still there matches
  EXPECT_EQ(j.takeReady().size(), 1u);
}

TEST(StepJoiner, OutOfOrderDuplicateAndMalformedTruthDropped) {
  StepJoiner j;
  j.addTruth(truth(2, 2));
  j.addTruth(truth(2, 2));  // duplicate stamp
  j.addTruth(truth(1, 2));  // older
  TruthSample twice = truth(3, 2);
  twice.uavs[1].id = 0;
  j.addTruth(twice);
  TruthSample negative = truth(4, 2);
  negative.uavs[0].id = -1;
  j.addTruth(negative);
  TruthSample ragged = truth(5, 2);
  ragged.agent_alive.pop_back();
  j.addTruth(ragged);
  const JoinCounters& c = j.counters();
  EXPECT_EQ(c.truth_samples, 1u);
  EXPECT_EQ(c.truth_duplicate, 1u);
  EXPECT_EQ(c.truth_out_of_order, 1u);
  EXPECT_EQ(c.truth_malformed, 3u);
  ASSERT_TRUE(j.newestTruth().has_value());
  EXPECT_EQ(*j.newestTruth(), 2 * kStep);
  EXPECT_EQ(j.flush().size(), 1u);
}

TEST(StepJoiner, NonFiniteInputsAreCountedButStillJoin) {
  StepJoiner j;
  TruthSample t = truth(0, 2);
  t.uavs[1].position_m.x() = std::numeric_limits<double>::quiet_NaN();
  j.addTruth(t);
  StateSample bad = state(0, 0);
  bad.finite = false;
  bad.estimate.valid = false;
  j.addState(bad);
  j.addState(state(1, 0));
  EXPECT_EQ(j.counters().truth_nonfinite_uavs, 1u);
  EXPECT_EQ(j.counters().state_nonfinite, 1u);
  const std::vector<JoinedStep> ready = j.takeReady();
  ASSERT_EQ(ready.size(), 1u);  // the NaN state completes its step, with no valid estimate
  EXPECT_FALSE(ready[0].states[0]->estimate.valid);
}

TEST(StepJoiner, FlushReleasesIncompleteStepsInOrder) {
  StepJoiner j;
  j.addTruth(truth(0, 2));
  j.addTruth(truth(1, 2));
  allStates(j, 1, 2);
  const std::vector<JoinedStep> rest = j.flush();
  ASSERT_EQ(rest.size(), 2u);
  EXPECT_EQ(rest[0].truth.stamp_ns, 0);
  EXPECT_EQ(rest[1].truth.stamp_ns, kStep);
  EXPECT_EQ(j.counters().missing_states, 2u);
  EXPECT_EQ(j.counters().steps_incomplete, 1u);
}

TEST(StepJoiner, HorizonMustBePositive) { EXPECT_THROW(StepJoiner(0), std::invalid_argument); }

// In lockstep the horizon's samples pass in a fraction of a second; a state lost on the wire and repaired after its
// writer's next heartbeat arrived "late" and the step was scored without it (a launch test under CPU load).
TEST(StepJoiner, IncompleteStepWaitsForTheGraceEvenPastTheHorizon) {
  // GIVEN a joiner with a horizon of 2 samples and 1 s of wall-clock grace, at wall time 10 s
  StepJoiner j(2, 1.0);
  j.advanceClock(10.0);
  // WHEN step 0 misses UAV 1's state and 5 newer complete steps arrive within 0.5 s
  j.addTruth(truth(0, 2));
  j.addState(state(0, 0));
  for (int k = 1; k <= 5; ++k) {
    j.addTruth(truth(k, 2));
    allStates(j, k, 2);
  }
  j.advanceClock(10.5);
  // THEN nothing is released: steps leave in order and step 0 may still complete
  EXPECT_TRUE(j.takeReady().empty());
  // WHEN the late state comes within the grace THEN every step is complete
  j.addState(state(1, 0));
  std::vector<JoinedStep> ready = j.takeReady();
  ASSERT_EQ(ready.size(), 6u);
  EXPECT_EQ(j.counters().steps_incomplete, 0u);
  EXPECT_EQ(j.counters().state_late, 0u);

  // GIVEN another incomplete step WHEN the grace has passed THEN it is released incomplete, the rest after it
  j.addTruth(truth(6, 2));
  for (int k = 7; k <= 9; ++k) {
    j.addTruth(truth(k, 2));
    allStates(j, k, 2);
  }
  j.advanceClock(11.49);
  EXPECT_TRUE(j.takeReady().empty());
  j.advanceClock(11.5);
  ready = j.takeReady();
  ASSERT_EQ(ready.size(), 4u);
  EXPECT_FALSE(ready[0].states[0].has_value());
  EXPECT_EQ(j.counters().steps_incomplete, 1u);
  EXPECT_EQ(j.counters().missing_states, 2u);
}

TEST(StepJoiner, PendingStepsAreBoundedWhateverTheGrace) {
  // GIVEN a grace that never passes and a UAV that never reports
  StepJoiner j(1, 1e9);
  // WHEN far more steps arrive than may be pending
  std::size_t released = 0;
  for (int k = 0; k < static_cast<int>(StepJoiner::kMaxPending) + 100; ++k) {
    j.addTruth(truth(k, 1));
    released += j.takeReady().size();
  }
  // THEN the oldest were released (incomplete), in order, and kMaxPending are left
  EXPECT_EQ(released, 100u);
  EXPECT_EQ(j.counters().steps_incomplete, 100u);
  EXPECT_EQ(j.flush().size(), StepJoiner::kMaxPending);
  EXPECT_THROW(StepJoiner(1, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace swa::monitor_node
