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

// Step k, complete: the truth of `n` UAVs, then every UAV's state.
void completeStep(StepJoiner& j, int k, int n) {
  j.addTruth(truth(k, n));
  allStates(j, k, n);
}

TEST(StepJoiner, StepCompleteOnceEveryLiveAgentReported) {
  // GIVEN a joiner with the truth of step 0 for 3 live agents
  StepJoiner j;
  j.addTruth(truth(0, 3));
  // WHEN UAVs 2 and 0 report THEN nothing is ready: the step waits for UAV 1
  j.addState(state(2, 0));
  j.addState(state(0, 0));
  EXPECT_TRUE(j.takeReady().empty());
  EXPECT_FALSE(j.idle());
  // WHEN UAV 1 reports too
  j.addState(state(1, 0));
  // THEN the step is ready with every state, in the truth's order, and nothing is incomplete or missing
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
  // GIVEN a joiner with the truth of step 0 for 3 UAVs, agent 1 dead
  StepJoiner j;
  j.addTruth(truth(0, 3, {1}));
  // WHEN the live agents 0 and 2 report
  j.addState(state(0, 0));
  j.addState(state(2, 0));
  // THEN the step is ready without UAV 1's state, and nothing counts as missing
  const std::vector<JoinedStep> ready = j.takeReady();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_FALSE(ready[0].states[1].has_value());
  EXPECT_EQ(j.counters().missing_states, 0u);  // a dead agent's state is not missing
}

TEST(StepJoiner, DeadAgentsStateIsStillUsedWhenItComes) {
  // GIVEN a joiner that has a state of dead agent 1 for step 0, from before the truth of step 0 arrived
  StepJoiner j;
  j.addState(state(1, 0, 4.0));  // the stalled agent still reports, before the truth
  // WHEN the truth comes, then live agent 0's state
  j.addTruth(truth(0, 2, {1}));
  j.addState(state(0, 0));
  // THEN the step is ready with agent 1's state in it
  const std::vector<JoinedStep> ready = j.takeReady();
  ASSERT_EQ(ready.size(), 1u);
  ASSERT_TRUE(ready[0].states[1].has_value());
  EXPECT_DOUBLE_EQ(ready[0].states[1]->estimate.position_m.x(), 4.0);
}

TEST(StepJoiner, StatesBeforeTheirTruthAreHeld) {
  // GIVEN a joiner that has every state of step 0 but no truth yet
  StepJoiner j;
  allStates(j, 0, 2);
  // THEN nothing is ready
  EXPECT_TRUE(j.takeReady().empty());
  // WHEN the truth of step 0 arrives THEN the step is ready, with every held state matched
  j.addTruth(truth(0, 2));
  EXPECT_EQ(j.takeReady().size(), 1u);
  EXPECT_EQ(j.counters().state_unmatched, 0u);
}

TEST(StepJoiner, MissingStateReleasedAfterHorizonInOrder) {
  // GIVEN a joiner with a horizon of 5 truth samples, and step 0 missing UAV 1's state
  StepJoiner j(5);
  j.addTruth(truth(0, 2));
  j.addState(state(0, 0));  // UAV 1 never reports for step 0
  // WHEN steps 1 to 4 arrive complete THEN none is released ahead of step 0
  for (int k = 1; k <= 4; ++k) {
    completeStep(j, k, 2);
    // Steps 1..4 are complete, but nothing overtakes step 0.
    EXPECT_TRUE(j.takeReady().empty()) << k;
  }
  // WHEN the truth of step 5 arrives
  j.addTruth(truth(5, 2));  // the 5th newer truth sample: step 0 goes, and the complete ones behind it
  // THEN steps 0 to 4 are released in order, step 0 without UAV 1's state, counted as incomplete and missing
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
  // GIVEN a joiner with a horizon of 1 sample, and step 0 released without UAV 1's state
  StepJoiner j(1);
  j.addTruth(truth(0, 2));
  j.addState(state(0, 0));
  j.addTruth(truth(1, 2));  // horizon 1: step 0 released without UAV 1
  ASSERT_EQ(j.takeReady().size(), 1u);
  // WHEN UAV 1's state of step 0 arrives THEN it is dropped and counted as late, not as unmatched
  j.addState(state(1, 0));
  EXPECT_EQ(j.counters().state_late, 1u);
  EXPECT_EQ(j.counters().state_unmatched, 0u);
}

TEST(StepJoiner, DuplicateStateFirstOneWins) {
  // GIVEN a joiner with the truth of step 0 for 2 UAVs
  StepJoiner j;
  j.addTruth(truth(0, 2));
  // WHEN UAV 0 reports twice, with different positions, then UAV 1
  j.addState(state(0, 0, 1.0));
  j.addState(state(0, 0, 2.0));
  j.addState(state(1, 0));
  // THEN the step holds UAV 0's first state and the second counts as a duplicate
  const std::vector<JoinedStep> ready = j.takeReady();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_DOUBLE_EQ(ready[0].states[0]->estimate.position_m.x(), 1.0);
  EXPECT_EQ(j.counters().state_duplicate, 1u);
  // WHEN a duplicate arrives before its truth (held) THEN it counts the same
  j.addState(state(0, kStep));
  j.addState(state(0, kStep));
  j.addTruth(truth(1, 2));
  EXPECT_EQ(j.counters().state_duplicate, 2u);
}

TEST(StepJoiner, StateOfUnknownUavIsDropped) {
  // GIVEN a joiner
  StepJoiner j;
  // WHEN a state of UAV 9 arrives before the truth of 2 UAVs, and one of UAV -1 after it
  j.addState(state(9, 0));  // held, then found not to be in the truth
  j.addTruth(truth(0, 2));
  j.addState(state(-1, 0));  // pending step, unknown id
  // THEN both are dropped as unknown UAVs
  EXPECT_EQ(j.counters().state_unknown_uav, 2u);
  // AND the step still completes with the real UAVs' states
  allStates(j, 0, 2);
  EXPECT_EQ(j.takeReady().size(), 1u);
}

TEST(StepJoiner, StatesForStampsNeverSeenAreUnmatched) {
  // GIVEN a joiner with the truth of step 1 for one UAV
  StepJoiner j;
  j.addTruth(truth(1, 1));
  // WHEN states stamped between steps 0 and 1 and between steps 1 and 2 arrive THEN the older is unmatched at once
  j.addState(state(0, kStep / 2));          // older than the newest truth, no truth with that stamp: at once
  j.addState(state(0, kStep + kStep / 2));  // newer: held ...
  EXPECT_EQ(j.counters().state_unmatched, 1u);
  // WHEN the truth of step 2 arrives THEN the held one is unmatched too
  j.addTruth(truth(2, 1));  // ... until a newer truth shows its stamp will never come
  EXPECT_EQ(j.counters().state_unmatched, 2u);
  // WHEN a state newer than every truth is still held at the end THEN flushing releases both steps and counts it
  // unmatched
  j.addState(state(0, 3 * kStep));                 // held
  const std::vector<JoinedStep> rest = j.flush();  // the end: held states are unmatched
  EXPECT_EQ(rest.size(), 2u);
  EXPECT_EQ(j.counters().state_unmatched, 3u);
  EXPECT_TRUE(j.idle());
}

TEST(StepJoiner, HeldStatesAreBounded) {
  // GIVEN a joiner with no truth yet
  StepJoiner j;
  // WHEN 10 more states arrive ahead of their truth than may be held
  const std::size_t extra = 10;
  for (std::size_t k = 0; k < StepJoiner::kMaxEarlyStates + extra; ++k) {
    j.addState(state(0, static_cast<agent::StampNs>(k + 1) * kStep));
  }
  // THEN the 10 oldest are dropped as unmatched
  EXPECT_EQ(j.counters().state_unmatched, extra);  // the oldest gave way
  // AND the oldest state still held matches its truth when that comes
  j.addTruth(truth(static_cast<int>(extra) + 1, 1));  // the oldest held stamp still there matches
  EXPECT_EQ(j.takeReady().size(), 1u);
}

TEST(StepJoiner, OutOfOrderDuplicateAndMalformedTruthDropped) {
  // GIVEN a joiner with the truth of step 2 for 2 UAVs
  StepJoiner j;
  j.addTruth(truth(2, 2));
  // WHEN the same stamp comes again, then an older one, then truth with a UAV id twice, a negative id, and fewer
  // agent flags than UAVs
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
  // THEN only the first is kept, and the others are counted as duplicate, out of order and malformed
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
  // GIVEN a joiner with the truth of step 0 in which UAV 1's position is NaN
  StepJoiner j;
  TruthSample t = truth(0, 2);
  t.uavs[1].position_m.x() = std::numeric_limits<double>::quiet_NaN();
  j.addTruth(t);
  // WHEN UAV 0's state is non-finite (no valid estimate) and UAV 1's is good
  StateSample bad = state(0, 0);
  bad.finite = false;
  bad.estimate.valid = false;
  j.addState(bad);
  j.addState(state(1, 0));
  // THEN both non-finite inputs are counted
  EXPECT_EQ(j.counters().truth_nonfinite_uavs, 1u);
  EXPECT_EQ(j.counters().state_nonfinite, 1u);
  // AND still join: the step is ready, with UAV 0's estimate invalid
  const std::vector<JoinedStep> ready = j.takeReady();
  ASSERT_EQ(ready.size(), 1u);  // the NaN state completes its step, with no valid estimate
  EXPECT_FALSE(ready[0].states[0]->estimate.valid);
}

TEST(StepJoiner, FlushReleasesIncompleteStepsInOrder) {
  // GIVEN a joiner with the truth of steps 0 and 1 for 2 UAVs, and only step 1's states
  StepJoiner j;
  j.addTruth(truth(0, 2));
  completeStep(j, 1, 2);
  // WHEN it is flushed (the end of the run)
  const std::vector<JoinedStep> rest = j.flush();
  // THEN both steps are released in order, step 0 incomplete with 2 missing states
  ASSERT_EQ(rest.size(), 2u);
  EXPECT_EQ(rest[0].truth.stamp_ns, 0);
  EXPECT_EQ(rest[1].truth.stamp_ns, kStep);
  EXPECT_EQ(j.counters().missing_states, 2u);
  EXPECT_EQ(j.counters().steps_incomplete, 1u);
}

TEST(StepJoiner, HorizonMustBePositive) {
  // WHEN a joiner is made with a horizon of 0 truth samples THEN it refuses
  EXPECT_THROW(StepJoiner(0), std::invalid_argument);
}

// In lockstep the horizon's samples pass in a fraction of a second; a state lost on the wire and repaired after its
// writer's next heartbeat arrived "late" and the step was scored without it (a launch test under CPU load).
TEST(StepJoiner, IncompleteStepWaitsForTheGraceEvenPastTheHorizon) {
  // GIVEN a joiner with a horizon of 2 samples and 1 s of wall-clock grace, at wall time 10 s
  StepJoiner j(2, 1.0);
  j.advanceClock(10.0);
  // WHEN step 0 misses UAV 1's state and 5 newer complete steps arrive within 0.5 s
  j.addTruth(truth(0, 2));
  j.addState(state(0, 0));
  for (int k = 1; k <= 5; ++k) completeStep(j, k, 2);
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
  for (int k = 7; k <= 9; ++k) completeStep(j, k, 2);
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
