#pragma once
// The one rule that drives an agent through its inputs (issue #28). The samples of one instant go IMU first, then
// detections, then GNSS: the command answers the IMU sample at once (the lowest loop latency, and the heading is
// known before the first detection set) and the detections and fix of that instant shape the next command, one IMU
// period later. The in-process loops (swa_batch, the tests) feed whole instants with feedInstant; swa_agent and
// swa_replay --check receive the samples one by one, put into the same order by the node's stamp orderer, and feed
// them through swa::wire::AgentFeed (swa/wire/agent_feed.h), which adds the messages' addressing and numbering.

#include <optional>

#include "swa/agent/agent.h"
#include "swa/agent/samples.h"

namespace swa::agent {

// One UAV's inputs of one instant, in the order above: the IMU sample's answer (fresh or not: a rejected sample's is
// not, and is not to be sent), or nothing without an IMU sample.
inline std::optional<VelocityCommand> feedInstant(Agent& agent, const std::optional<ImuSample>& imu,
                                                  const std::optional<DetectionSet>& detections,
                                                  const std::optional<GnssSample>& gnss) {
  std::optional<VelocityCommand> answer;
  if (imu) answer = agent.onImu(*imu);
  if (detections) agent.onDetections(*detections);
  if (gnss) agent.onGnss(*gnss);
  return answer;
}

}  // namespace swa::agent
