#pragma once
// swa/swarm/mission (SwarmMission) <-> the agent core's MissionCommand (swa/agent/mission.h), both directions. What
// comes off the wire is not trusted: a kind this build does not know makes the whole command unreadable (never a
// guess); whether a readable one can be flown is the agent's question (missionCommandProblem).

#include <cstdint>
#include <string>
#include <variant>

#include <swa/msg/SwarmMission.h>

#include "swa/agent/mission.h"

namespace swa::wire {

msg::SwarmMission toMsg(const agent::MissionCommand& command, std::int64_t stamp_ns, std::uint32_t seq);

// The command, or why it cannot be read.
std::variant<agent::MissionCommand, std::string> missionCommandOf(const msg::SwarmMission& m);

}  // namespace swa::wire
