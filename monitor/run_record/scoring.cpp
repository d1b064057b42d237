#include "swa/run_record/scoring.h"

namespace swa::record {

Scoring scoringOf(const sim::Scenario& scenario) {
  Scoring s;
  s.metrics.formation = scenario.agent.formation;
  s.metrics.window_start_s = sim::driftWindowStart(scenario);
  s.score_estimates = scenario.agent.mode != agent::Mode::kStandalone;
  return s;
}

}  // namespace swa::record
