// The pure parts of the DDS adapters, without DDS traffic: sample ordering, lockstep bookkeeping, message
// command lines, domain resolution (the message conversions are tested in tests/msgs).

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "agent_options.h"
#include "lockstep_tracker.h"
#include "sample_order.h"
#include "silence_watch.h"
#include "sim_options.h"
#include "swa/app/stall_watch.h"
#include "swa/dds/options.h"
#include "swa/dds/sample_queue.h"
#include "swa/dds/topics.h"
#include "world_pause.h"

namespace swa {
namespace {

using agent_node::Stream;
using Orderer = agent_node::StampOrderer<int>;

constexpr agent::StampNs kMs = 1'000'000;

std::vector<int> drain(Orderer& o) {
  std::vector<int> out;
  while (auto e = o.pop()) out.push_back(e->payload);
  return out;
}

// ---- StampOrderer: every arrival order of one step gives the closed loop's order ------------------------------

TEST(StampOrderer, EqualStampsGoImuThenDetectionsThenGnssWhateverTheArrivalOrder) {
  // GIVEN the three samples of one step arriving GNSS first, IMU last
  Orderer o(1000 * kMs);
  o.push(Stream::kGnss, 100 * kMs, 3);
  o.push(Stream::kDetections, 100 * kMs, 2);
  // THEN nothing leaves before the IMU sample of that step is there
  EXPECT_TRUE(drain(o).empty());
  o.push(Stream::kImu, 100 * kMs, 1);
  // THEN IMU, detections, GNSS
  EXPECT_EQ(drain(o), (std::vector<int>{1, 2, 3}));
}

TEST(StampOrderer, ImuLeavesAtOnceAndLateSideSamplesFollowIt) {
  Orderer o(1000 * kMs);
  o.push(Stream::kImu, 0, 1);
  EXPECT_EQ(drain(o), (std::vector<int>{1}));
  // Detections of the same step arriving after the IMU was processed leave at once.
  o.push(Stream::kDetections, 0, 2);
  EXPECT_EQ(drain(o), (std::vector<int>{2}));
}

TEST(StampOrderer, OlderSideSampleQueuedWithNextImuGoesFirst) {
  // GIVEN detections of step k and the IMU of step k+1 waiting together
  Orderer o(1000 * kMs);
  o.push(Stream::kImu, 0, 1);
  drain(o);
  o.push(Stream::kImu, 10 * kMs, 3);
  o.push(Stream::kDetections, 0, 2);
  // THEN stamp order
  EXPECT_EQ(drain(o), (std::vector<int>{2, 3}));
}

TEST(StampOrderer, WithoutImuSideSamplesLeaveAfterTheHoldLimit) {
  // GIVEN a sensor setup without IMU
  Orderer o(1000 * kMs);
  o.push(Stream::kDetections, 0, 1);
  o.push(Stream::kDetections, 500 * kMs, 2);
  EXPECT_TRUE(drain(o).empty());
  // WHEN a sample more than the hold limit newer arrives
  o.push(Stream::kGnss, 1600 * kMs, 3);
  // THEN the ones older than the limit leave, in order
  EXPECT_EQ(drain(o), (std::vector<int>{1, 2}));
  EXPECT_EQ(o.size(), 1u);
}

TEST(StampOrderer, ExtremeStampsDoNotOverflow) {
  Orderer o(1000 * kMs);
  o.push(Stream::kDetections, std::numeric_limits<agent::StampNs>::min(), 1);
  o.push(Stream::kDetections, std::numeric_limits<agent::StampNs>::max(), 2);
  EXPECT_EQ(drain(o), (std::vector<int>{1}));
}

TEST(StampOrderer, FarFutureSideSamplesAreNotHeld) {
  // GIVEN an IMU stream at 5 s
  Orderer o(1000 * kMs);
  o.push(Stream::kImu, 5000 * kMs, 1);
  drain(o);
  // WHEN 10000 detection sets arrive stamped an hour, and INT64_MAX, ahead (the issue's +43 MB/s)
  for (int i = 0; i < 10000; ++i) {
    o.push(Stream::kDetections, i % 2 == 0 ? 3'600'000 * kMs : std::numeric_limits<agent::StampNs>::max(), 2);
    EXPECT_EQ(drain(o), (std::vector<int>{2}));  // THEN each leaves at once (the core rejects its stamp)
  }
  EXPECT_EQ(o.size(), 0u);
  EXPECT_EQ(o.forcedReleases(), 10000u);
  // AND the normal order is unaffected: a set of the next step still waits for its IMU
  o.push(Stream::kDetections, 5010 * kMs, 3);
  EXPECT_TRUE(drain(o).empty());
  o.push(Stream::kImu, 5010 * kMs, 4);
  EXPECT_EQ(drain(o), (std::vector<int>{4, 3}));
}

TEST(StampOrderer, NeverHoldsMoreThanItsBound) {
  // GIVEN no IMU and side samples that creep forward by 1 ns (never more than the hold limit apart)
  Orderer o(1000 * kMs, 64);
  std::size_t released = 0;
  for (int i = 0; i < 100000; ++i) {
    o.push(Stream::kDetections, i, i);
    released += drain(o).size();
    ASSERT_LE(o.size(), 64u);
  }
  // THEN the orderer stays at its bound and releases the oldest, in order
  EXPECT_EQ(o.size(), 64u);
  EXPECT_EQ(released, 100000u - 64u);
  EXPECT_EQ(o.forcedReleases(), 100000u - 64u);
}

// ---- StallWatch -----------------------------------------------------------------------------------------------

TEST(StallWatch, OnlyGapsBeyondTheLoopsOwnWaitCount) {
  using C = app::StallWatch::Clock;
  app::StallWatch w(std::chrono::milliseconds(250));
  const C::time_point t0{};
  EXPECT_EQ(w.check(t0), C::duration::zero());  // the first check starts the watch
  EXPECT_EQ(w.check(t0 + std::chrono::milliseconds(100)), C::duration::zero());
  EXPECT_EQ(w.check(t0 + std::chrono::milliseconds(350)), C::duration::zero());  // exactly the allowed gap
  // a 2 s SIGSTOP between two checks: 2 s + 100 ms of gap, 1.85 s of it beyond the loop's 250 ms
  EXPECT_EQ(w.check(t0 + std::chrono::milliseconds(2450)), std::chrono::milliseconds(1850));
  EXPECT_EQ(w.stalls(), 1);
  // a known wait is not a stall
  w.restart(t0 + std::chrono::milliseconds(9000));
  EXPECT_EQ(w.check(t0 + std::chrono::milliseconds(9100)), C::duration::zero());
  EXPECT_EQ(w.total(), std::chrono::milliseconds(1850));
}

// ---- SilenceWatch ---------------------------------------------------------------------------------------------

using WatchClock = agent_node::SilenceWatch::Clock;
constexpr auto kSilenceLimit = std::chrono::seconds(6);

// Polls every 20 ms (as AgentNode::run does) from `now` for `span`, moving `now`; returns the first report, if any.
std::optional<WatchClock::duration> pollFor(agent_node::SilenceWatch& w, WatchClock::time_point& now,
                                            WatchClock::duration span, bool arriving, bool expected, int writers) {
  const WatchClock::time_point end = now + span;
  for (; now < end; now += std::chrono::milliseconds(20)) {
    if (auto r = w.poll(now, arriving, expected, writers)) return r;
  }
  return std::nullopt;
}

TEST(SilenceWatch, SamplesThatStopAreReportedAtTheLimitThenCountedAfresh) {
  agent_node::SilenceWatch w(kSilenceLimit);
  WatchClock::time_point now{};
  EXPECT_FALSE(pollFor(w, now, std::chrono::seconds(1), true, true, 1));  // healthy: samples arrive
  const WatchClock::time_point stopped = now;
  const auto report = pollFor(w, now, std::chrono::seconds(20), false, true, 1);
  ASSERT_TRUE(report);
  EXPECT_GE(*report, kSilenceLimit);
  EXPECT_LT(*report, kSilenceLimit + std::chrono::milliseconds(40));  // the last poll with samples, then 6 s
  EXPECT_LT(now - stopped, kSilenceLimit + std::chrono::milliseconds(40));
  // after a reconnection that did not help, the next report is a whole limit later, not at the next poll
  now += std::chrono::milliseconds(20);
  const WatchClock::time_point first = now;
  ASSERT_TRUE(pollFor(w, now, std::chrono::seconds(20), false, true, 1));
  EXPECT_GE(now - first, kSilenceLimit - std::chrono::milliseconds(20));
}

TEST(SilenceWatch, OnePollWithSamplesStartsTheCountOver) {
  agent_node::SilenceWatch w(kSilenceLimit);
  WatchClock::time_point now{};
  // 5.9 s without a sample, one poll with one, 5.9 s again: a slow writer, never a broken channel
  for (int round = 0; round < 5; ++round) {
    EXPECT_FALSE(pollFor(w, now, std::chrono::milliseconds(5900), false, true, 1)) << "round " << round;
    EXPECT_FALSE(w.poll(now, true, true, 1));
    now += std::chrono::milliseconds(20);
  }
}

TEST(SilenceWatch, NothingIsOwedWhilePausedOrWithoutAWriter) {
  agent_node::SilenceWatch w(kSilenceLimit);
  WatchClock::time_point now{};
  EXPECT_FALSE(w.poll(now, true, true, 1));
  // the agent itself stopped, or had no sample yet: nothing owed, for a minute
  EXPECT_FALSE(pollFor(w, now, std::chrono::seconds(60), false, false, 1));
  // it resumes: the count starts at the resumption, not at the last sample a minute ago
  EXPECT_FALSE(pollFor(w, now, std::chrono::seconds(5), false, true, 1));
  // no matched writer: nobody owes a sample
  EXPECT_FALSE(pollFor(w, now, std::chrono::seconds(60), false, true, 0));
  // restart(): a new participant is owed nothing, whatever came before
  EXPECT_FALSE(pollFor(w, now, std::chrono::seconds(5), false, true, 1));
  w.restart();
  EXPECT_FALSE(pollFor(w, now, std::chrono::seconds(5), false, true, 1));
}

// ---- WorldPause ----------------------------------------------------------------------------------------------

TEST(WorldPause, ATickHeardTwiceMeansTheSimulatorWaitsForTheRepeatWindow) {
  agent_node::WorldPause p;
  WatchClock::time_point now{};
  // a running lockstep simulator: a new step every tick, never a wait
  for (std::uint64_t step = 0; step < 500; ++step, now += std::chrono::milliseconds(2)) {
    p.tick(step, now);
    EXPECT_FALSE(p.waiting(now)) << "step " << step;
  }
  // it waits on step 499 and says so once a second
  now += std::chrono::seconds(1);
  p.tick(499, now);
  EXPECT_TRUE(p.waiting(now));
  EXPECT_TRUE(p.waiting(now + agent_node::WorldPause::kRepeatWindow - std::chrono::milliseconds(1)));
  // its ticks stop too (a simulator gone, or this agent's own port deaf): the pause is over after the window
  EXPECT_FALSE(p.waiting(now + agent_node::WorldPause::kRepeatWindow));
  // it goes on: a new step is no wait, even right after a repeat
  now += std::chrono::seconds(1);
  p.tick(500, now);
  EXPECT_TRUE(p.waiting(now));  // the repeat a second ago still counts: the silence it covered owed nothing
  now += agent_node::WorldPause::kRepeatWindow;
  p.tick(501, now);
  EXPECT_FALSE(p.waiting(now));
}

TEST(WorldPause, NoTickAtAllIsNoPause) {
  // a drone with no simulator: nobody publishes the clock, and silence keeps its meaning
  const agent_node::WorldPause p;
  EXPECT_FALSE(p.waiting(WatchClock::time_point{}));
  EXPECT_FALSE(p.waiting(WatchClock::time_point{} + std::chrono::hours(1)));
}

// ---- LockstepTracker ------------------------------------------------------------------------------------------

TEST(LockstepTracker, WaitsForEveryLiveAgentWithAnImuSample) {
  sim_node::LockstepTracker t(3);
  t.begin({0, 0, std::nullopt});  // UAV 2 has no IMU sample this step: not waited for
  EXPECT_FALSE(t.complete());
  EXPECT_EQ(t.onAnswer(0, 0), sim_node::Verdict::kApply);
  EXPECT_EQ(t.onAnswer(0, 0), sim_node::Verdict::kIgnore);  // duplicate
  EXPECT_FALSE(t.complete());
  EXPECT_EQ(t.waitingFor(), (std::vector<int>{1}));
  EXPECT_EQ(t.onAnswer(1, 5), sim_node::Verdict::kIgnore);  // answers a stamp never sent
  EXPECT_EQ(t.onAnswer(1, 0), sim_node::Verdict::kApply);
  EXPECT_TRUE(t.complete());
  EXPECT_EQ(t.onAnswer(7, 0), sim_node::Verdict::kIgnore);  // unknown UAV
}

TEST(LockstepTracker, NewcomerThenDeadThenRejoinedWhenCaughtUp) {
  sim_node::LockstepTracker t(2);
  // GIVEN step 0 where agent 1 never answers
  t.begin({0, 0});
  EXPECT_EQ(t.onAnswer(0, 0), sim_node::Verdict::kApply);
  EXPECT_TRUE(t.waitingForNewcomer());
  EXPECT_EQ(t.expire(), (std::vector<int>{1}));
  EXPECT_FALSE(t.alive(1));
  EXPECT_EQ(t.aliveCount(), 1);
  // WHEN steps go on without it
  t.begin({10, 10});
  EXPECT_FALSE(t.complete());
  EXPECT_EQ(t.onAnswer(0, 10), sim_node::Verdict::kApply);
  EXPECT_TRUE(t.complete());
  t.begin({20, 20});
  // THEN an answer older than the previous step is ignored (still catching up) ...
  EXPECT_EQ(t.onAnswer(1, 0), sim_node::Verdict::kIgnore);
  EXPECT_FALSE(t.alive(1));
  // ... an answer to the previous step rejoins it, and it is waited for again from this step on
  EXPECT_EQ(t.onAnswer(1, 10), sim_node::Verdict::kRejoin);
  EXPECT_TRUE(t.alive(1));
  EXPECT_EQ(t.onAnswer(0, 20), sim_node::Verdict::kApply);
  EXPECT_FALSE(t.complete());
  EXPECT_FALSE(t.waitingForNewcomer());  // it has answered before: the agent timeout applies
  EXPECT_EQ(t.onAnswer(1, 20), sim_node::Verdict::kApply);
  EXPECT_TRUE(t.complete());
}

TEST(LockstepTracker, DeadAgentAnsweringTheCurrentStepIsDoneForIt) {
  sim_node::LockstepTracker t(1);
  t.begin({0});
  t.expire();
  t.begin({10});
  EXPECT_TRUE(t.complete());  // nobody alive to wait for
  EXPECT_EQ(t.onAnswer(0, 10), sim_node::Verdict::kRejoin);
  EXPECT_TRUE(t.complete());
}

TEST(LockstepTracker, DeadAgentAnsweringAgainIsWaitedForUntilItCatchesUp) {
  // GIVEN agent 1 declared dead at step 10, and steps going on with agent 0 alone
  sim_node::LockstepTracker t(2);
  t.begin({0, 0});
  EXPECT_EQ(t.onAnswer(0, 0), sim_node::Verdict::kApply);
  EXPECT_EQ(t.onAnswer(1, 0), sim_node::Verdict::kApply);
  t.begin({10, 10});
  EXPECT_EQ(t.onAnswer(0, 10), sim_node::Verdict::kApply);
  EXPECT_EQ(t.expire(), (std::vector<int>{1}));
  t.begin({20, 20});
  EXPECT_EQ(t.onAnswer(0, 20), sim_node::Verdict::kApply);
  // THEN an answer from before its death (a late packet) earns nothing: nobody is waited for
  EXPECT_EQ(t.onAnswer(1, 0), sim_node::Verdict::kIgnore);
  EXPECT_TRUE(t.complete());
  t.begin({30, 30});
  EXPECT_EQ(t.onAnswer(0, 30), sim_node::Verdict::kApply);
  // WHEN it answers the step it missed: it runs again, two steps behind
  EXPECT_EQ(t.onAnswer(1, 10), sim_node::Verdict::kIgnore);
  // THEN it is still dead, but the step waits for it, as it would for a live agent
  EXPECT_FALSE(t.alive(1));
  EXPECT_FALSE(t.complete());
  EXPECT_EQ(t.waitingFor(), (std::vector<int>{1}));
  EXPECT_FALSE(t.waitingForNewcomer());  // it has answered before: the agent timeout applies
  // AND when it does not make it within the timeout, it stays dead without being declared dead again
  EXPECT_EQ(t.expire(), (std::vector<int>{}));
  EXPECT_TRUE(t.complete());
  // AND the same answer again earns no second wait; a newer one does
  t.begin({40, 40});
  EXPECT_EQ(t.onAnswer(0, 40), sim_node::Verdict::kApply);
  EXPECT_EQ(t.onAnswer(1, 10), sim_node::Verdict::kIgnore);
  EXPECT_TRUE(t.complete());
  EXPECT_EQ(t.onAnswer(1, 20), sim_node::Verdict::kIgnore);
  EXPECT_FALSE(t.complete());
  // WHEN it catches up: the previous step's answer rejoins it, this step's completes the step
  t.begin({50, 50});
  EXPECT_EQ(t.onAnswer(0, 50), sim_node::Verdict::kApply);
  EXPECT_EQ(t.onAnswer(1, 40), sim_node::Verdict::kRejoin);
  EXPECT_TRUE(t.alive(1));
  EXPECT_FALSE(t.complete());
  EXPECT_EQ(t.onAnswer(1, 50), sim_node::Verdict::kApply);
  EXPECT_TRUE(t.complete());
}

// ---- Command lines ---------------------------------------------------------------------------------------------

TEST(AgentOptions, ParsesEveryOption) {
  const auto o = agent_node::parseAgentOptions(
      {"--id", "3", "--config=a.yaml", "--set", "formation.k=2", "--set", "control.k_p=0.4", "--domain", "7"});
  EXPECT_EQ(o.id, 3);
  EXPECT_EQ(o.config_path, "a.yaml");
  EXPECT_EQ(o.overrides, (std::vector<std::string>{"formation.k=2", "control.k_p=0.4"}));
  ASSERT_TRUE(o.domain.has_value());
  EXPECT_EQ(*o.domain, "7");
  EXPECT_TRUE(agent_node::parseAgentOptions({"--help"}).help);
}

// The agent reads its own section only (issue #47); a scenario given to it says where that section comes from.
TEST(AgentOptions, AScenarioIsRefusedWithWhereTheAgentsConfigurationComesFrom) {
  for (const std::vector<std::string>& args : {std::vector<std::string>{"--id", "0", "--scenario", "s.yaml"},
                                               std::vector<std::string>{"--id", "0", "--scenario=s.yaml"}}) {
    try {
      agent_node::parseAgentOptions(args);
      FAIL() << "a scenario accepted: " << args[2];
    } catch (const std::invalid_argument& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("DIR/agent.yaml"), std::string::npos) << m;
      EXPECT_NE(m.find("--export-agent-config"), std::string::npos) << m;
    }
  }
}

TEST(AgentOptions, RejectsBadIdsAndReportsEveryProblem) {
  for (const char* bad : {"-1", "abc", "3.5", "", "10000", " 3", "3x"}) {
    EXPECT_THROW(agent_node::parseAgentOptions({"--id", bad}), std::invalid_argument) << bad;
  }
  EXPECT_THROW(agent_node::parseAgentOptions({}), std::invalid_argument);
  try {
    agent_node::parseAgentOptions({"--id", "x", "--frobnicate", "--config"});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    for (const char* needle : {"--id 'x'", "--frobnicate", "--config needs a value"}) {
      EXPECT_NE(m.find(needle), std::string::npos) << needle << " missing from: " << m;
    }
  }
}

TEST(SimOptions, ParsesEveryOptionAndReportsEveryProblem) {
  const auto o = sim_node::parseSimOptions({"--scenario", "s.yaml", "--set", "duration_s=20", "--domain=9",
                                            "--agent-timeout-s", "0.5", "--startup-timeout-s", "10", "--truth-every",
                                            "1", "--truth-out", "t.csv", "--summary-out", "s.json"});
  EXPECT_EQ(o.scenario_path, "s.yaml");
  EXPECT_EQ(o.overrides, (std::vector<std::string>{"duration_s=20"}));
  EXPECT_EQ(*o.domain, "9");
  EXPECT_EQ(o.agent_timeout_s, 0.5);
  EXPECT_EQ(o.startup_timeout_s, 10.0);
  EXPECT_EQ(o.truth_every, 1);
  EXPECT_EQ(o.truth_out, "t.csv");
  EXPECT_EQ(o.summary_out, "s.json");
  try {
    sim_node::parseSimOptions({"--agent-timeout-s", "0", "--truth-every", "0", "--bogus"});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    for (const char* needle : {"--agent-timeout-s", "--truth-every", "--bogus"}) {
      EXPECT_NE(m.find(needle), std::string::npos) << needle << " missing from: " << m;
    }
  }
  EXPECT_THROW(sim_node::parseSimOptions({}), std::invalid_argument);  // --scenario is required
  EXPECT_THROW(sim_node::parseSimOptions({"--agent-timeout-s", "nan", "--scenario", "s"}), std::invalid_argument);
}

// A secured start needs room for a stalled handshake's re-creation and a stuck participant's restart (sim_options.h).
TEST(SimOptions, StartupTimeoutIsLongerWithSecurityUnlessGiven) {
  ::unsetenv("SWA_SECURITY_DIR");
  EXPECT_EQ(sim_node::parseSimOptions({"--scenario", "s"}).startup_timeout_s, 60.0);
  ::setenv("SWA_SECURITY_DIR", "/nonexistent", 1);
  EXPECT_EQ(sim_node::parseSimOptions({"--scenario", "s"}).startup_timeout_s, 120.0);
  EXPECT_EQ(sim_node::parseSimOptions({"--scenario", "s", "--startup-timeout-s", "30"}).startup_timeout_s, 30.0);
  ::setenv("SWA_SECURITY_DIR", "", 1);  // set but empty: security off
  EXPECT_EQ(sim_node::parseSimOptions({"--scenario", "s"}).startup_timeout_s, 60.0);
  ::unsetenv("SWA_SECURITY_DIR");
}

TEST(DomainResolution, CommandLineThenEnvironmentThenZero) {
  ::unsetenv("SWA_DOMAIN");
  EXPECT_EQ(dds::resolveDomain(std::nullopt), 0);
  EXPECT_EQ(dds::resolveDomain(std::string("12")), 12);
  ::setenv("SWA_DOMAIN", "33", 1);
  EXPECT_EQ(dds::resolveDomain(std::nullopt), 33);
  EXPECT_EQ(dds::resolveDomain(std::string("4")), 4);
  ::setenv("SWA_DOMAIN", "300", 1);
  EXPECT_THROW(dds::resolveDomain(std::nullopt), std::invalid_argument);
  ::unsetenv("SWA_DOMAIN");
  EXPECT_THROW(dds::resolveDomain(std::string("-1")), std::invalid_argument);
  EXPECT_THROW(dds::resolveDomain(std::string("233")), std::invalid_argument);
}

TEST(Topics, PerUavNames) {
  EXPECT_EQ(dds::topics::imu(3), "swa/uav3/imu");
  EXPECT_EQ(dds::topics::detections(0), "swa/uav0/detections");
  EXPECT_EQ(dds::topics::gnss(12), "swa/uav12/gnss");
  EXPECT_EQ(dds::topics::cmdVel(1), "swa/uav1/cmd_vel");
  EXPECT_EQ(dds::topics::state(1), "swa/uav1/state");
  EXPECT_STREQ(dds::topics::kTruth, "swa/truth");
}

TEST(SampleQueue, DrainTakesEverythingInArrivalOrder) {
  dds::SampleQueue<int> q;
  std::vector<int> out;
  EXPECT_FALSE(q.drain(out, std::chrono::milliseconds(0)));
  q.push(1);
  q.push(2);
  EXPECT_TRUE(q.drain(out, std::chrono::milliseconds(0)));
  EXPECT_EQ(out, (std::vector<int>{1, 2}));
  q.wake();
  EXPECT_FALSE(q.drain(out, std::chrono::hours(1)));  // returns at once: woken
}

}  // namespace
}  // namespace swa
