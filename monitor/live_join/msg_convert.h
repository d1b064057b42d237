#pragma once
// swa/truth, swa/uav<i>/state and swa/events messages -> the monitor's input types (monitor_inputs.h). Only the
// generated message types are included here, no DDS entity.

#include <optional>

#include <swa/msg/AgentState.h>
#include <swa/msg/ScenarioEvent.h>
#include <swa/msg/SwarmTruth.h>

#include "monitor_inputs.h"
#include "swa/agent/config.h"

namespace swa::monitor_node {

// Ids are taken as the simulator wrote them; a non-finite position or velocity is kept (the metrics leave that UAV
// out of the step, monitor::isPresent) and counted by the caller.
TruthSample fromTruthMsg(const msg::SwarmTruth& m);

// The agent's estimate as monitor::estimateFromDiagnostics would see the agent's own diagnostics: valid only for
// mode swa / anchored, stage tracking, a valid frame and at least one neighbour. The message does not carry the
// agent's formation radius and fit: `formation` supplies them (the scenario's agent.formation). Unknown mode or
// stage values and non-finite numbers make the estimate invalid.
StateSample fromStateMsg(const msg::AgentState& m, const agent::FormationConfig& formation);

// nullopt for a kind value this build does not know.
std::optional<EventRecord> fromEventMsg(const msg::ScenarioEvent& m);

}  // namespace swa::monitor_node
