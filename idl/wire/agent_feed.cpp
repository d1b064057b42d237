#include "swa/wire/agent_feed.h"

#include "swa/wire/samples.h"

namespace swa::wire {

std::optional<msg::VelocitySetpoint> AgentFeed::onImu(const msg::Imu& m) {
  if (!isFor(m.uav_id())) return std::nullopt;
  const agent::VelocityCommand command = agent_.onImu(fromMsg(m));
  if (!command.fresh) return std::nullopt;
  return toMsg(command, uav_id_, ++command_seq_, m.header().seq());
}

bool AgentFeed::onDetections(const msg::Detections& m) {
  if (!isFor(m.observer_id())) return false;
  agent_.onDetections(fromMsg(m));
  return true;
}

bool AgentFeed::onGnss(const msg::GnssFix& m) {
  if (!isFor(m.uav_id())) return false;
  agent_.onGnss(fromMsg(m));
  return true;
}

}  // namespace swa::wire
