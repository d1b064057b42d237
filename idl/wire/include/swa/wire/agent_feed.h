#pragma once
// One agent fed SWA's messages one at a time, in the order of swa/agent/feed.h (the caller orders them: swa_agent's
// stamp orderer, swa_replay's recording): what swa_agent and swa_replay --check share. A message addressed to another
// UAV is not fed (the caller counts it); an IMU sample the agent accepted is answered with the command message,
// numbered on, stamped with the sample it answers; a rejected one is not answered (a flood of bad samples must not
// become a flood of commands).

#include <cstdint>
#include <optional>

#include <swa/msg/Detections.h>
#include <swa/msg/GnssFix.h>
#include <swa/msg/Imu.h>
#include <swa/msg/VelocitySetpoint.h>

#include "swa/agent/agent.h"

namespace swa::wire {

class AgentFeed {
 public:
  AgentFeed(agent::Agent& agent, std::uint32_t uav_id) : agent_(agent), uav_id_(uav_id) {}

  bool isFor(std::uint32_t named_uav) const { return named_uav == uav_id_; }

  // nullopt: addressed to another UAV, or not answered.
  std::optional<msg::VelocitySetpoint> onImu(const msg::Imu& m);
  // false: addressed to another UAV (not fed).
  bool onDetections(const msg::Detections& m);
  bool onGnss(const msg::GnssFix& m);

 private:
  agent::Agent& agent_;
  std::uint32_t uav_id_;
  std::uint32_t command_seq_ = 0;
};

}  // namespace swa::wire
