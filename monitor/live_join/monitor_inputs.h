#pragma once
// What the monitor takes from the swarm, free of DDS types: one truth sample, one agent state, one scenario event.
// msg_convert.h builds them from the messages; everything downstream (join, metrics, files) sees only these.

#include <optional>
#include <string>
#include <vector>

#include "swa/agent/config.h"
#include "swa/agent/samples.h"
#include "swa/monitor/swarm_metrics.h"
#include "swa/sim/events.h"

namespace swa::monitor_node {

inline double stampSeconds(agent::StampNs stamp_ns) { return static_cast<double>(stamp_ns) * 1e-9; }

// One swa/truth sample.
struct TruthSample {
  agent::StampNs stamp_ns = 0;
  // Every UAV of the scenario. UavTruth::alive is true for all: the simulator's `alive` flag says whether the
  // AGENT answers, and a UAV whose agent died hovers under the failsafe, still in the air and in every metric.
  std::vector<monitor::UavTruth> uavs;
  std::vector<bool> agent_alive;  // per entry of `uavs`: the simulator's `alive` flag
};

// One swa/uav<i>/state sample.
struct StateSample {
  int uav = -1;                      // uav_id the agent reports
  agent::StampNs stamp_ns = 0;       // the IMU sample after which the agent was in this state
  std::optional<agent::Mode> mode;   // nullopt: a mode value this build does not know
  bool finite = true;                // false: a non-finite estimate or covariance (then estimate.valid is false)
  monitor::EstimateRecord estimate;  // monitor::estimateFromDiagnostics of the state
};

// Events are spelled as the run record holds them (swa/sim/events.h).
using sim::EventRecord;
using sim::kAllUavs;
namespace event_kind = sim::event_kind;

}  // namespace swa::monitor_node
