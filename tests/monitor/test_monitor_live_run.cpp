// LiveRun, the live monitor without DDS: steps go to the metrics in stamp order whatever the arrival order, a dead
// agent's UAV stays in the metrics, the metrics window comes from the scenario or from the GNSS loss event, and
// the end event, mode, events and status are what the node and the files need.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "live_config.h"
#include "live_record.h"
#include "live_run.h"
#include "status_line.h"
#include "swa/run_record/run_dir.h"

namespace swa::monitor_node {
namespace {

using record::Outcome;

constexpr agent::StampNs kLiveStep = 100'000'000;

// Four UAVs on a 10 m square drifting east at 0.1 m/s; agent `dead` (if >= 0) is not alive from step 10 on.
TruthSample square(int k, int dead = -1) {
  TruthSample t;
  t.stamp_ns = k * kLiveStep;
  const double x0 = 0.01 * k;
  const agent::Vec2 corners[] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  for (int i = 0; i < 4; ++i) {
    monitor::UavTruth u;
    u.id = i;
    u.position_m = corners[i] + agent::Vec2(x0, 0.0);
    u.velocity_mps = agent::Vec2(0.1, 0.0);
    t.uavs.push_back(u);
    t.agent_alive.push_back(!(i == dead && k >= 10));
  }
  return t;
}

// A tracking agent estimate, exact except for a small offset, with neighbours = the other three UAVs.
StateSample estimate(int uav, int k) {
  StateSample s;
  s.uav = uav;
  s.stamp_ns = k * kLiveStep;
  s.mode = agent::Mode::kSwa;
  s.estimate.valid = true;
  s.estimate.position_m = agent::Vec2(0.1, -0.1);
  s.estimate.position_cov_m2 = agent::Mat2::Identity() * 0.05;
  s.estimate.velocity_cov_m2ps2 = agent::Mat2::Identity() * 0.01;
  int n = 0;
  for (int j = 0; j < 4; ++j) {
    if (j != uav) s.estimate.neighbour_ids[static_cast<std::size_t>(n++)] = j;
  }
  s.estimate.neighbour_count = n;
  return s;
}

EventRecord event(double t_s, const char* kind, int uav, const char* text = "") {
  EventRecord e;
  e.t_s = t_s;
  e.kind = kind;
  e.uav = uav;
  e.text = text;
  return e;
}

LiveRunConfig config(double window_start_s) {
  LiveRunConfig c;
  c.metrics.window_start_s = window_start_s;
  c.mode = agent::Mode::kSwa;
  return c;
}

TEST(LiveRun, ScoresStepsInStampOrderWhateverTheArrivalOrder) {
  // GIVEN two live runs of a 4-UAV square drifting east, every agent tracking
  LiveRun in_order(config(0.0));
  LiveRun scrambled(config(0.0));
  // WHEN one gets 30 steps in order, truth first
  for (int k = 0; k < 30; ++k) {
    in_order.onTruth(square(k));
    for (int i = 0; i < 4; ++i) in_order.onState(i, estimate(i, k));
  }
  // AND the other the same samples scrambled
  for (int k = 0; k < 30; k += 2) {
    // States of step k+1 first, then truth k+1, then step k's states, then its truth.
    for (int i = 3; i >= 0; --i) scrambled.onState(i, estimate(i, k + 1));
    for (int i = 0; i < 4; ++i) scrambled.onState(i, estimate(i, k));
    scrambled.onTruth(square(k));
    scrambled.onTruth(square(k + 1));
  }
  // THEN, once finished, both scored the 30 steps identically, row for row and in the summary
  in_order.finish();
  scrambled.finish();
  ASSERT_EQ(in_order.series().size(), 30u);
  ASSERT_EQ(scrambled.series().size(), 30u);
  for (std::size_t k = 0; k < 30; ++k) {
    EXPECT_EQ(monitor::formatCsvRow(in_order.series()[k]), monitor::formatCsvRow(scrambled.series()[k])) << k;
  }
  EXPECT_EQ(record::metricsJson(in_order.summary()).dump(), record::metricsJson(scrambled.summary()).dump());
  // AND nothing was missing, and every estimate was scored
  EXPECT_EQ(scrambled.joinCounters().missing_states, 0u);
  EXPECT_EQ(in_order.summary().nees_samples, 4u * 30u);
}

TEST(LiveRun, DeadAgentsUavStaysInTheMetricsWithoutAnEstimate) {
  // GIVEN a live run of 20 steps in which agent 3 is dead from step 10 on and sends no more states
  LiveRun run(config(0.0));
  for (int k = 0; k < 20; ++k) {
    run.onTruth(square(k, 3));
    for (int i = 0; i < 4; ++i) {
      if (i != 3 || k < 10) run.onState(i, estimate(i, k));
    }
  }
  // THEN the join did not wait for the dead agent: every step is scored before finish()
  EXPECT_TRUE(run.joinIdle());
  EXPECT_EQ(run.series().size(), 20u);
  // AND, finished, its UAV is still in the geometry (4 UAVs) but only its 10 live steps have NEES samples, nothing
  // counts as missing, and 3 of 4 agents are live
  run.finish();
  const monitor::Summary s = run.summary();
  EXPECT_EQ(s.uav_count, 4);  // still flying (failsafe hover): still in d_NB, separation, groups
  EXPECT_EQ(s.nees_samples, 4u * 10u + 3u * 10u);
  EXPECT_EQ(run.joinCounters().missing_states, 0u);
  EXPECT_EQ(run.status().live_agents, 3);
  EXPECT_EQ(run.status().uavs, 4);
  // AND the run ended with UAV 3 on failsafe: its record FAILs for that alone (the formation held), naming it
  EXPECT_EQ(run.failsafeNow(), (std::vector<int>{3}));
  const RunRecord r = makeRunRecord(run, config(0.0), RunContext{"", "", std::nullopt, 0.1, {true, "completed"}, {}});
  EXPECT_EQ(r.verdict.outcome, Outcome::kFail) << record::verdictText(r.verdict);
  ASSERT_EQ(r.verdict.reasons.size(), 1u) << record::verdictText(r.verdict);
  EXPECT_EQ(r.verdict.reasons[0], "UAV 3 on failsafe at the end (agent declared dead, never rejoined)");
}

TEST(LiveRun, AnAgentThatRejoinsLeavesNoUavOnFailsafe) {
  // GIVEN agent 2 dead for steps 10 to 14, alive again from step 15 (the truth's alive flags)
  LiveRun run(config(0.0));
  for (int k = 0; k < 20; ++k) {
    TruthSample t = square(k);
    t.agent_alive[2] = !(k >= 10 && k < 15);
    run.onTruth(t);
    for (int i = 0; i < 4; ++i) {
      if (i != 2 || k < 10 || k >= 15) run.onState(i, estimate(i, k));
    }
    if (k == 12) {
      EXPECT_EQ(run.failsafeNow(), (std::vector<int>{2}));
    }
  }
  run.finish();
  // THEN none is on failsafe at the end, and the run passes
  EXPECT_TRUE(run.failsafeNow().empty());
  const RunRecord r = makeRunRecord(run, config(0.0), RunContext{"", "", std::nullopt, 0.1, {true, "completed"}, {}});
  EXPECT_EQ(r.verdict.outcome, Outcome::kPass) << record::verdictText(r.verdict);
}

TEST(LiveRun, MissingStatesWaitForTheHorizonThenScoreWithoutThem) {
  // GIVEN a live run with a join horizon of 5 truth samples
  LiveRunConfig c = config(0.0);
  c.join_horizon = 5;
  LiveRun run(c);
  // WHEN agent 3, alive, sends nothing for steps 0 to 4
  for (int k = 0; k < 5; ++k) {
    run.onTruth(square(k));
    for (int i = 0; i < 3; ++i) run.onState(i, estimate(i, k));  // agent 3 alive but silent
  }
  // THEN no step is scored while it may still come
  EXPECT_TRUE(run.series().empty());
  // WHEN the truth of step 5 arrives THEN step 0 is scored without it
  run.onTruth(square(5));
  EXPECT_EQ(run.series().size(), 1u);
  // WHEN step 5's states come and the run finishes THEN all 6 steps are scored, agent 3's 6 states missing
  for (int i = 0; i < 3; ++i) run.onState(i, estimate(i, 5));
  run.finish();
  EXPECT_EQ(run.series().size(), 6u);
  EXPECT_EQ(run.joinCounters().missing_states, 6u);
  EXPECT_EQ(run.summary().nees_samples, 3u * 6u);
}

TEST(LiveRun, StateOnAnotherUavsTopicIsDropped) {
  // GIVEN a live run with the truth of step 0
  LiveRun run(config(0.0));
  run.onTruth(square(0));
  // WHEN UAV 0's state arrives on UAV 1's topic THEN it is dropped as an unknown UAV
  run.onState(1, estimate(0, 0));  // topic of UAV 1 carrying UAV 0's state
  EXPECT_EQ(run.joinCounters().state_unknown_uav, 1u);
}

TEST(LiveRun, WithoutEstimateScoringThereIsNoNees) {
  // GIVEN a live run that does not score estimates
  LiveRunConfig c = config(0.0);
  c.score_estimates = false;
  LiveRun run(c);
  // WHEN 3 steps with tracking estimates arrive
  for (int k = 0; k < 3; ++k) {
    run.onTruth(square(k));
    for (int i = 0; i < 4; ++i) run.onState(i, estimate(i, k));
  }
  // THEN there is no NEES sample, and the time series' NEES is NaN
  run.finish();
  EXPECT_EQ(run.summary().nees_samples, 0u);
  EXPECT_TRUE(std::isnan(run.series().back().nees_pos));
}

TEST(LiveRun, WindowFromScenarioIsUsedAsGiven) {
  // GIVEN a live run whose scenario starts the metrics window at 1 s
  LiveRun run(config(1.0));
  // WHEN a GNSS loss event for all UAVs at 2 s and 30 steps of truth arrive
  run.onEvent(event(2.0, event_kind::kGnssLost, kAllUavs));  // ignored: the scenario decides
  for (int k = 0; k < 30; ++k) run.onTruth(square(k, -1));
  run.finish();
  // THEN the window starts at 1 s
  EXPECT_DOUBLE_EQ(run.windowStartS(), 1.0);
  EXPECT_NEAR(run.summary().window_start_s, 1.0, 1e-9);
}

TEST(LiveRun, WindowFromTheGnssLossEventWhenThereIsNoScenario) {
  // GIVEN live runs without a scenario, fed 40 steps of truth and the given events before or after them
  const auto runWith = [](const std::vector<EventRecord>& events, bool events_last) {
    LiveRunConfig c = liveRunConfigWithoutScenario();
    auto run = std::make_unique<LiveRun>(c);
    if (!events_last) {
      for (const EventRecord& e : events) run->onEvent(e);
    }
    for (int k = 0; k < 40; ++k) run->onTruth(square(k));
    for (const EventRecord& e : events) {
      if (events_last) run->onEvent(e);
    }
    run->finish();
    return run;
  };
  // WHEN a GNSS loss for all UAVs and an earlier one for UAV 2 arrive after the steps THEN the one for all UAVs sets
  // the window start
  auto run = runWith({event(1.5, event_kind::kGnssLost, 2), event(2.0, event_kind::kGnssLost, kAllUavs)}, true);
  EXPECT_DOUBLE_EQ(run->windowStartS(), 2.0);
  EXPECT_NEAR(run->summary().window_start_s, 2.0, 1e-9);
  // WHEN there are only per-UAV GNSS loss events THEN the earliest sets it
  run = runWith({event(2.5, event_kind::kGnssLost, 1), event(1.5, event_kind::kGnssLost, 2)}, false);
  EXPECT_DOUBLE_EQ(run->windowStartS(), 1.5);
  // WHEN there is no GNSS loss event THEN the window starts at 0
  run = runWith({event(1.0, event_kind::kGnssRestored, 1)}, false);
  EXPECT_DOUBLE_EQ(run->windowStartS(), 0.0);
  EXPECT_NEAR(run->summary().window_start_s, 0.0, 1e-9);
  // AND the summary of a run whose window came from the event is that of a run with the window from a scenario
  LiveRun direct(config(1.5));
  for (int k = 0; k < 40; ++k) direct.onTruth(square(k));
  direct.finish();
  run = runWith({event(1.5, event_kind::kGnssLost, 0)}, true);
  EXPECT_EQ(record::metricsJson(run->summary()).dump(), record::metricsJson(direct.summary()).dump());
}

TEST(LiveRun, EndEventModeAndEvents) {
  // GIVEN a live run without a scenario
  LiveRunConfig c = liveRunConfigWithoutScenario();
  LiveRun run(c);
  // THEN it has no mode before any state
  EXPECT_FALSE(run.mode().has_value());
  // WHEN an anchored agent's state arrives THEN the run's mode is anchored
  run.onTruth(square(0));
  StateSample s = estimate(0, 0);
  s.mode = agent::Mode::kAnchored;
  run.onState(0, s);
  ASSERT_TRUE(run.mode().has_value());
  EXPECT_EQ(*run.mode(), agent::Mode::kAnchored);
  // WHEN two scenario-end events, a collision and an unknown event arrive
  run.onEvent(event(3.0, event_kind::kScenarioEnd, kAllUavs, "completed"));
  run.onEvent(event(1.0, event_kind::kCollision, 1));
  run.onEvent(event(4.0, event_kind::kScenarioEnd, kAllUavs, "interrupted"));
  run.onUnknownEvent();
  // THEN the first scenario end is the run's end, every known event is kept in time order, and the unknown one is
  // counted
  ASSERT_TRUE(run.endEvent().has_value());
  EXPECT_EQ(run.endEvent()->text, "completed");  // the first one
  const std::vector<EventRecord> events = run.events();
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].kind, event_kind::kCollision);  // by time
  EXPECT_EQ(run.unknownEvents(), 1u);
}

TEST(LiveRun, EndEventMeaning) {
  // WHEN the scenario-end event's text is "completed" THEN the run completed
  EXPECT_TRUE(endFromEvent(event(1, event_kind::kScenarioEnd, kAllUavs, "completed")).completed);
  // WHEN it is anything else THEN the run did not complete, and the reason carries the text
  const RunEnd interrupted = endFromEvent(event(1, event_kind::kScenarioEnd, kAllUavs, "discovery timeout"));
  EXPECT_FALSE(interrupted.completed);
  EXPECT_NE(interrupted.reason.find("discovery timeout"), std::string::npos);
}

TEST(LiveRun, RunRecordCarriesVerdictCountsAndContext) {
  // GIVEN a live run of a 4-UAV square for 60 steps, every agent tracking, plus one truth sample out of order
  const LiveRunConfig c = config(0.0);
  LiveRun run(c);
  for (int k = 0; k < 60; ++k) {
    run.onTruth(square(k));
    for (int i = 0; i < 4; ++i) run.onState(i, estimate(i, k));
  }
  run.onTruth(square(3));  // out of order
  run.finish();
  // AND the context: scenario, seed, a completed end, one restart
  RunContext ctx;
  ctx.scenario = "s.yaml";
  ctx.seed = 9;
  ctx.end = {true, "completed"};
  ctx.restarts.restarts = {{1.0, 2, "1", 1, 0.5}};
  // WHEN its run record is made
  const RunRecord r = makeRunRecord(run, c, ctx);
  // THEN it carries the mode as the label, the mode, the seed, a PASS, the whole series and the restart
  EXPECT_EQ(r.label, "swa");  // the mode when no label is given
  EXPECT_EQ(r.mode, "swa");
  EXPECT_EQ(r.seed, std::optional<std::uint64_t>(9));
  EXPECT_EQ(r.verdict.outcome, Outcome::kPass);  // a 10 m square: d_NB = 10 m, one group, no collision
  EXPECT_EQ(r.series.size(), 60u);
  EXPECT_EQ(r.restarts.restarts.size(), 1u);
  // AND the dropped out-of-order truth sample is counted
  bool found = false;
  for (const auto& [key, n] : r.counts) {
    if (key == "dropped_truth_out_of_order") {
      EXPECT_EQ(n, 1u);
      found = true;
    }
  }
  EXPECT_TRUE(found);
  // WHEN a label is given and the run was interrupted THEN the record has that label and is INCOMPLETE
  ctx.label = "mine";
  ctx.end = {false, "interrupted by SIGINT"};
  const RunRecord r2 = makeRunRecord(run, c, ctx);
  EXPECT_EQ(r2.label, "mine");
  EXPECT_EQ(r2.verdict.outcome, Outcome::kIncomplete);
}

TEST(LiveRun, NothingReceivedIsIncomplete) {
  // GIVEN a live run without a scenario that received nothing
  const LiveRunConfig c = liveRunConfigWithoutScenario();
  LiveRun run(c);
  run.finish();
  // WHEN its run record is made for a completed end
  const RunRecord r = makeRunRecord(run, c, RunContext{"", "", std::nullopt, 0.1, {true, "completed"}, {}});
  // THEN it is INCOMPLETE, of mode unknown, with no series
  EXPECT_EQ(r.verdict.outcome, Outcome::kIncomplete);
  EXPECT_EQ(r.mode, "unknown");
  EXPECT_TRUE(r.series.empty());
}

TEST(StatusLine, FormatsTheLatestStep) {
  // GIVEN a status before any step
  LiveStatus s;
  // THEN it says that it waits for ground truth
  EXPECT_EQ(formatStatus(s), "waiting for ground truth");
  // WHEN a step was scored (one value not available)
  s.any_step = true;
  s.t_s = 12.34;
  s.d_nb_m = 9.876;
  s.min_sep_m = monitor::kNaN;
  s.collisions = 2;
  s.groups = 1;
  s.live_agents = 3;
  s.uavs = 4;
  // THEN one line shows time, d_NB, separation, collisions, groups and live agents, n/a for the missing value
  EXPECT_EQ(formatStatus(s), "t 12.3 s  d_NB 9.88 m  min sep n/a m  collisions 2  groups 1  agents 3/4 live");
}

TEST(StatusLine, PacerEveryTenSimSecondsInALogAndByWallTimeOnATerminal) {
  // GIVEN a pacer for a log
  LiveStatus s;
  StatusPacer log(false);
  // THEN it prints nothing before the first step
  EXPECT_FALSE(log.due(s, 0.0));  // nothing to say before the first step
  // WHEN steps come every 0.1 s of simulated time for 25 s
  s.any_step = true;
  std::vector<double> printed;
  for (int k = 0; k <= 250; ++k) {
    s.t_s = 0.1 * k;
    if (log.due(s, 0.0)) printed.push_back(s.t_s);
  }
  // THEN it prints at 0 s and at the first steps after 10 s and 20 s
  ASSERT_EQ(printed.size(), 3u);
  EXPECT_DOUBLE_EQ(printed[0], 0.0);
  EXPECT_NEAR(printed[1], 10.0, 0.1 + 1e-9);  // the first step in [10, 20)
  EXPECT_NEAR(printed[2], 20.0, 0.1 + 1e-9);

  // GIVEN a pacer for a terminal, every 0.25 s of wall time
  StatusPacer tty(true, 0.25);
  // THEN it prints at wall time 0 s, not at 0.1 s, again at 0.3 s, not at 0.5 s
  EXPECT_TRUE(tty.due(s, 0.0));
  EXPECT_FALSE(tty.due(s, 0.1));
  EXPECT_TRUE(tty.due(s, 0.3));
  EXPECT_FALSE(tty.due(s, 0.5));
}

}  // namespace
}  // namespace swa::monitor_node
