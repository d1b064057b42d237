#include "live_config.h"

namespace swa::monitor_node {

LiveRunConfig liveRunConfig(const sim::Scenario& scenario) {
  LiveRunConfig c;
  c.metrics.formation_radius_m = scenario.agent.formation.radius_m;
  c.metrics.window_start_s = sim::driftWindowStart(scenario);
  c.window_from_events = false;
  // As swa_batch's closed loop: standalone agents estimate in their take-off frame, nothing to score.
  c.score_estimates = scenario.agent.mode != agent::Mode::kStandalone;
  c.mode = scenario.agent.mode;
  c.formation = scenario.agent.formation;
  return c;
}

LiveRunConfig liveRunConfigWithoutScenario() {
  LiveRunConfig c;
  c.formation = agent::FormationConfig{};
  c.metrics.formation_radius_m = c.formation.radius_m;
  c.window_from_events = true;
  // Every state is converted with monitor::estimateFromDiagnostics rules, so standalone agents' estimates are
  // invalid anyway and count as "no estimate".
  c.score_estimates = true;
  return c;
}

}  // namespace swa::monitor_node
