#pragma once
// What the monitor takes from the swarm, free of DDS types: one truth sample, one agent state, one scenario event.
// msg_convert.h builds them from the messages; everything downstream (join, metrics, files) sees only these.

#include <optional>
#include <string>
#include <vector>

#include "swa/agent/config.h"
#include "swa/agent/samples.h"
#include "swa/monitor/swarm_metrics.h"

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

// Event kinds as written to events.csv and summary.json.
namespace event_kind {
inline constexpr const char* kGnssLost = "gnss_lost";
inline constexpr const char* kGnssRestored = "gnss_restored";
inline constexpr const char* kAgentDead = "agent_dead";
inline constexpr const char* kAgentRejoined = "agent_rejoined";
inline constexpr const char* kCollision = "collision";
inline constexpr const char* kFailsafe = "failsafe";
inline constexpr const char* kScenarioEnd = "scenario_end";
}  // namespace event_kind

// uav / other_uav value of an event about every UAV (ScenarioEvent.idl ALL_UAVS) or about no second UAV.
constexpr int kAllUavs = -1;

// One swa/events sample.
struct EventRecord {
  double t_s = 0.0;  // sim time the event took effect
  std::string kind;  // one of event_kind
  int uav = kAllUavs;
  int other_uav = -1;
  double value = 0.0;
  std::string text;
};

}  // namespace swa::monitor_node
