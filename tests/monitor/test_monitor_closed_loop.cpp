// swa_monitor scores a run exactly as swa_batch does: the in-process closed loop is run here once more, but its
// truth and agent diagnostics go through the messages (the wire bridge the simulator and the agents use) and the
// monitor's join, in scrambled order; the time series and summary must be identical to runClosedLoop's, bit for
// bit. With one agent dead half-way, the geometry is unchanged (its UAV still flies) and only its NEES is missing.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <swa/msg/SwarmTruth.h>

#include "closed_loop.h"
#include "live_config.h"
#include "live_run.h"
#include "msg_convert.h"
#include "swa/agent/agent.h"
#include "swa/agent/feed.h"
#include "swa/sim/scenario_io.h"
#include "swa/sim/world.h"
#include "swa/wire/agent_state.h"
#include "swa/wire/world.h"

namespace swa::monitor_node {
namespace {

sim::Scenario scenario(const std::string& mode) {
  return sim::parseScenario(
      "uav_count: 4\nseed: 3\nduration_s: 20.0\ngnss:\n  dropout_start_s: 5.0\nagent:\n  mode: " + mode + "\n",
      "test scenario");
}

msg::SwarmTruth truthMsg(const sim::World& world, int dead_agent) {
  wire::SwarmTruth truth{world.time_ns(), world.truth(), {}};
  for (const sim::UavTruth& t : truth.uavs) truth.agent_alive.push_back(t.id != dead_agent);
  return wire::toMsg(truth, 0);
}

// The closed loop of runClosedLoop, feeding a LiveRun through the messages. From `dead_from_s` on, agent
// `dead_agent` keeps flying its UAV (the world is unchanged) but the truth calls it dead and its states stop.
std::unique_ptr<LiveRun> monitorLoop(const sim::Scenario& s, int dead_agent = -1, double dead_from_s = 1e9) {
  const LiveRunConfig config = liveRunConfig(s);
  auto live = std::make_unique<LiveRun>(config);
  sim::World world(s);
  const int n = world.uav_count();
  std::vector<agent::Agent> agents(static_cast<std::size_t>(n), agent::Agent(s.agent));
  std::vector<StateSample> held;  // states of odd steps, delivered after the next truth sample
  std::uint32_t seq = 0;
  while (true) {
    const std::vector<sim::UavSensors>& sensors = world.sensors();
    for (int i = 0; i < n; ++i) {
      agent::Agent& a = agents[static_cast<std::size_t>(i)];
      const sim::UavSensors& in = sensors[static_cast<std::size_t>(i)];
      if (const auto command = agent::feedInstant(a, in.imu, in.detections, in.gnss)) world.command(i, *command);
    }
    if (world.step_index() % 10 == 0 || world.finished()) {
      const bool dead_now = world.time_ns() >= static_cast<agent::StampNs>(dead_from_s * 1e9);
      std::vector<StateSample> states;
      for (int i = n - 1; i >= 0; --i) {  // reverse UAV order on purpose
        if (dead_now && i == dead_agent) continue;
        msg::AgentState m =
            wire::toMsg(agents[static_cast<std::size_t>(i)].diagnostics(), static_cast<std::uint32_t>(i), ++seq);
        m.header().stamp_ns(world.time_ns());
        states.push_back(fromStateMsg(m, config.metrics.formation));
      }
      const bool odd = (world.step_index() / 10) % 2 == 1;
      if (!odd) {
        for (const StateSample& st : states) live->onState(st.uav, st);  // states before their truth
      }
      live->onTruth(fromTruthMsg(truthMsg(world, dead_now ? dead_agent : -1)));
      for (const StateSample& st : held) live->onState(st.uav, st);  // the previous odd step's, late
      held.clear();
      if (odd) held = states;
    }
    if (world.finished()) break;
    world.step();
  }
  for (const StateSample& st : held) live->onState(st.uav, st);
  live->finish();
  return live;
}

void expectSameSummary(const monitor::Summary& a, const monitor::Summary& b) {
  const auto fa = monitor::summaryFields(a);
  const auto fb = monitor::summaryFields(b);
  ASSERT_EQ(fa.size(), fb.size());
  for (std::size_t k = 0; k < fa.size(); ++k) {
    const bool same = (std::isnan(fa[k].value) && std::isnan(fb[k].value)) || fa[k].value == fb[k].value;
    EXPECT_TRUE(same) << fa[k].key << ": " << fa[k].value << " vs " << fb[k].value;
  }
}

TEST(MonitorClosedLoop, ReproducesSwaBatchExactly) {
  for (const std::string mode : {"swa", "standalone"}) {
    SCOPED_TRACE(mode);
    // GIVEN the 4-UAV GNSS-loss scenario (20 s) in this mode, and swa_batch's in-process run of it as the reference
    const sim::Scenario s = scenario(mode);
    const batch::RunResult reference = batch::runClosedLoop(s);
    // WHEN the same loop's truth and agent states reach the monitor through the messages, states early and late
    const std::unique_ptr<LiveRun> live = monitorLoop(s);
    // THEN the monitor's time series is swa_batch's, row for row
    ASSERT_EQ(live->series().size(), reference.series.size());
    for (std::size_t k = 0; k < reference.series.size(); ++k) {
      ASSERT_EQ(monitor::formatCsvRow(live->series()[k]), monitor::formatCsvRow(reference.series[k])) << k;
    }
    // AND so is its summary, bit for bit, with no state missing, late or unmatched
    expectSameSummary(live->summary(), reference.summary);
    EXPECT_EQ(live->joinCounters().missing_states, 0u);
    EXPECT_EQ(live->joinCounters().state_late + live->joinCounters().state_unmatched, 0u);
    // AND with estimates to score (SWA mode) it scored NEES samples
    if (mode == "swa") {
      EXPECT_GT(live->summary().nees_samples, 0u);
    }
  }
}

TEST(MonitorClosedLoop, DeadAgentKeepsItsUavInTheGeometry) {
  // GIVEN the SWA-mode scenario and swa_batch's reference run of it
  const sim::Scenario s = scenario("swa");
  const batch::RunResult reference = batch::runClosedLoop(s);
  // WHEN agent 2 is dead from 10 s on (its UAV still flies, its states stop)
  const std::unique_ptr<LiveRun> live = monitorLoop(s, 2, 10.0);
  const monitor::Summary a = live->summary();
  const monitor::Summary& b = reference.summary;
  // THEN the geometry is the reference's: the dead agent's UAV is still in it
  EXPECT_EQ(a.uav_count, b.uav_count);
  EXPECT_EQ(a.mean_neighbor_distance_m, b.mean_neighbor_distance_m);
  EXPECT_EQ(a.min_separation_m, b.min_separation_m);
  EXPECT_EQ(a.collisions, b.collisions);
  EXPECT_EQ(a.groups, b.groups);
  EXPECT_EQ(a.drift_velocity_mps, b.drift_velocity_mps);
  // AND there are fewer NEES samples (agent 2's are missing), no state was waited for, and 3 agents are live
  EXPECT_LT(a.nees_samples, b.nees_samples);           // agent 2's estimates are missing from 10 s on
  EXPECT_EQ(live->joinCounters().missing_states, 0u);  // a dead agent is not waited for
  EXPECT_EQ(live->status().live_agents, 3);
}

}  // namespace
}  // namespace swa::monitor_node
