#pragma once
// swa/uav<i>/state (AgentState) <-> the agent core's diagnostics (agent/include/swa/agent/diagnostics.h), both
// directions, field for field. The agent node publishes toMsg(); the monitor reads fromMsg() and scores the estimate
// with monitor::estimateFromDiagnostics, as swa_batch does with the agent's own diagnostics.

#include <cstddef>
#include <cstdint>
#include <optional>

#include <swa/msg/AgentState.h>

#include "swa/agent/diagnostics.h"

namespace swa::wire {

// Bound of AgentState.neighbour_ids in the IDL; fastddsgen 2.3 does not enforce it, so the publisher cuts.
constexpr std::size_t kMaxStateNeighbourIds = 64;

msg::AgentState toMsg(const agent::Diagnostics& d, std::uint32_t uav_id, std::uint32_t seq);

// What an AgentState says, in the core's terms. Values off the wire are not trusted: an id above INT_MAX is -1 (no
// UAV has it), an enum value this build does not know is nullopt (the diagnostics then hold the standalone mode /
// the initializing stage, which are never scored), STAGE_NO_INPUT reads as kLost (not tracking). Neighbour ids
// beyond what the core holds keep their count, so the set reads as impossible rather than truncated.
struct AgentStateSample {
  int uav = -1;
  std::optional<agent::Mode> mode;
  std::optional<agent::Stage> stage;
  bool no_input = false;  // STAGE_NO_INPUT: no valid IMU sample for a second or more
  agent::Diagnostics diagnostics;
};

AgentStateSample fromMsg(const msg::AgentState& m);

}  // namespace swa::wire
