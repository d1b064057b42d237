#include "live_config.h"

#include "swa/run_record/scoring.h"

namespace swa::monitor_node {

LiveRunConfig liveRunConfig(const sim::Scenario& scenario) {
  LiveRunConfig c;
  const record::Scoring scoring = record::scoringOf(scenario);  // as swa_batch's closed loop
  c.metrics = scoring.metrics;
  c.score_estimates = scoring.score_estimates;
  c.failure_hint = scoring.failure_hint;
  c.window_from_events = false;
  c.mode = scenario.agent.mode;
  return c;
}

LiveRunConfig liveRunConfigWithoutScenario() {
  LiveRunConfig c;
  c.window_from_events = true;
  // Every state is converted with monitor::estimateFromDiagnostics rules, so standalone agents' estimates are
  // invalid anyway and count as "no estimate".
  c.score_estimates = true;
  return c;
}

}  // namespace swa::monitor_node
