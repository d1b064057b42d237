#include "closed_loop.h"

#include <cmath>

#include "swa/agent/agent.h"
#include "swa/agent/feed.h"
#include "swa/monitor/swarm_metrics.h"
#include "swa/run_record/scoring.h"
#include "swa/sim/world.h"

namespace swa::batch {

RunResult runClosedLoop(const sim::Scenario& scenario, const LoopOptions& options) {
  sim::World world(scenario);
  const int n = world.uav_count();
  std::vector<agent::Agent> agents(static_cast<std::size_t>(n), agent::Agent(scenario.agent));

  const record::Scoring scoring = record::scoringOf(scenario);  // as the live monitor's
  monitor::MetricsAccumulator metrics(scoring.metrics);
  const bool score_estimates = scoring.score_estimates;

  RunResult result;
  result.seed = scenario.seed;
  result.mode = scenario.agent.mode;
  monitor::TrajectoryRecorder trajectories;
  monitor::StepInput input;
  input.uavs.resize(static_cast<std::size_t>(n));
  if (score_estimates) input.estimates.resize(static_cast<std::size_t>(n));

  while (true) {
    result.events.insert(result.events.end(), world.events().begin(), world.events().end());
    const std::vector<sim::UavSensors>& sensors = world.sensors();
    for (int i = 0; i < n; ++i) {
      agent::Agent& a = agents[static_cast<std::size_t>(i)];
      const sim::UavSensors& s = sensors[static_cast<std::size_t>(i)];
      // One instant in the order of swa/agent/feed.h, as the DDS agent processes it.
      if (const auto command = agent::feedInstant(a, s.imu, s.detections, s.gnss)) world.command(i, *command);
    }
    if (world.step_index() % options.metrics_every_steps == 0 || world.finished()) {
      input.stamp_ns = world.time_ns();
      const std::vector<sim::UavTruth>& truth = world.truth();
      for (int i = 0; i < n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        input.uavs[k] = monitor::UavTruth{truth[k].id, truth[k].position_m, truth[k].velocity_mps, true};
        if (score_estimates) {
          input.estimates[k] = monitor::estimateFromDiagnostics(agents[k].diagnostics(), scenario.agent.formation);
        }
      }
      result.series.push_back(monitor::toRow(metrics.add(input)));
      trajectories.add(static_cast<double>(input.stamp_ns) * 1e-9, input.uavs);
    }
    if (world.finished()) break;
    world.step();
  }
  result.summary = metrics.summary();
  result.trajectories = trajectories.trajectories();
  for (const agent::Agent& a : agents) result.rejected_inputs += a.diagnostics().rejected.total();
  return result;
}

double meanNeighbourDistanceAt(const RunResult& run, double t_s, double window_s) {
  constexpr double kSlackS = 1e-9;  // row times are sums of 0.1 s steps
  double sum = 0.0;
  int n = 0;
  for (const monitor::TimeSeriesRow& row : run.series) {
    if (row.t_s > t_s - window_s + kSlackS && row.t_s <= t_s + kSlackS && std::isfinite(row.d_nb_m)) {
      sum += row.d_nb_m;
      ++n;
    }
  }
  return n > 0 ? sum / n : monitor::kNaN;
}

}  // namespace swa::batch
