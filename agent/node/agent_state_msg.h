#pragma once
// Agent diagnostics -> swa::msg::AgentState (the swa/uav<i>/state topic).

#include <cstdint>

#include <swa/msg/AgentState.h>

#include "swa/agent/diagnostics.h"

namespace swa::agent_node {

// Bound of AgentState.neighbour_ids in the IDL; fastddsgen 2.3 does not enforce it, so the publisher cuts.
constexpr std::size_t kMaxStateNeighbourIds = 64;

msg::AgentState toStateMsg(const agent::Diagnostics& d, std::uint32_t uav_id, std::uint32_t seq);

}  // namespace swa::agent_node
