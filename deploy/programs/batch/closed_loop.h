#pragma once
// The in-process closed loop: the simulated world and one agent core per UAV, stepped together. This is the fast
// path for Monte Carlo work and the oracle the DDS system must agree with: no threads, no clock, so a scenario and
// seed always give the same run.

#include <vector>

#include "swa/monitor/accumulator.h"
#include "swa/monitor/report_html.h"
#include "swa/monitor/summary_format.h"
#include "swa/sim/scenario.h"
#include "swa/sim/world.h"

namespace swa::batch {

struct RunResult {
  std::uint64_t seed = 0;
  agent::Mode mode = agent::Mode::kSwa;
  monitor::Summary summary;
  std::vector<monitor::TimeSeriesRow> series;        // one row per metrics sample
  std::uint64_t rejected_inputs = 0;                 // summed over agents: should be 0 for simulated sensors
  std::vector<sim::Event> events;                    // everything the world raised (GNSS loss, collisions, failsafe)
  std::vector<monitor::UavTrajectory> trajectories;  // true positions, one point per UAV every 0.5 s
};

struct LoopOptions {
  int metrics_every_steps = 10;  // 10 Hz metrics at the default 100 Hz dynamics
};

RunResult runClosedLoop(const sim::Scenario& scenario, const LoopOptions& options = {});

// d_NB "at" time t_s with the summary's end-of-run definition: the mean over the metrics rows in (t_s - window, t_s].
// NaN when no row there has one.
double meanNeighbourDistanceAt(const RunResult& run, double t_s, double window_s = 5.0);

}  // namespace swa::batch
