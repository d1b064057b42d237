#pragma once
// How a run of a scenario is scored, the same for the in-process loop (swa_batch) and the live monitor.

#include <string>

#include "swa/monitor/accumulator.h"
#include "swa/sim/scenario.h"

namespace swa::record {

struct Scoring {
  monitor::MetricsConfig
      metrics;  // the agents' formation, and drift measured from the common GNSS loss (sim::driftWindowStart)
  // Standalone agents estimate in their take-off frame: there is no floating frame to score their estimates against.
  bool score_estimates = true;
  // Why the run may fail for a reason of the world the metrics cannot see, said with a FAIL verdict (empty: none).
  std::string failure_hint;
};

Scoring scoringOf(const sim::Scenario& scenario);

}  // namespace swa::record
