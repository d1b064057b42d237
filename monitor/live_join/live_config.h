#pragma once
// How a live run is scored: from the scenario when one is given (exactly as swa_batch scores it), else from the
// defaults and the events of the run (live_run.h LiveRunConfig::window_from_events).

#include "live_run.h"
#include "swa/sim/scenario.h"

namespace swa::monitor_node {

// r = agent.formation.radius_m, window from sim::driftWindowStart, no NEES for standalone agents.
LiveRunConfig liveRunConfig(const sim::Scenario& scenario);

// r = 10 m (the agents' default formation), window from the GNSS loss event, NEES for whatever agents report a
// floating-frame estimate.
LiveRunConfig liveRunConfigWithoutScenario();

}  // namespace swa::monitor_node
