#include "swa/run_record/scoring.h"

#include <cmath>

#include "swa/monitor/svg_plot.h"

namespace swa::record {

Scoring scoringOf(const sim::Scenario& scenario) {
  Scoring s;
  s.metrics.formation = scenario.agent.formation;
  s.metrics.window_start_s = sim::driftWindowStart(scenario);
  s.score_estimates = scenario.agent.mode != agent::Mode::kStandalone;
  if (const double start = sim::missionStart(scenario); std::isfinite(start)) {
    s.metrics.mission_legs = scenario.agent.mission.legs;
    s.metrics.mission_start_s = start;
  }
  // Issue #44: every UAV leans into a steady wind alike, and a tilt-reading agent takes the lean for acceleration.
  if (scenario.wind.mean_mps > 0.0 && scenario.agent.focal.imu_source == agent::ImuSource::kTilt) {
    s.failure_hint = "the agents read their acceleration from the tilt (imu.source tilt) in a mean wind of " +
                     monitor::formatFixed(scenario.wind.mean_mps, 1) +
                     " m/s: each takes its lean into the wind for acceleration, all alike, which nothing "
                     "relative can see, so the swarm rides the wind (imu.source accelerometer sees the wind's push)";
  }
  return s;
}

}  // namespace swa::record
