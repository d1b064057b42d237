#pragma once
// The sensor and command messages <-> the agent core's sample types (agent/include/swa/agent/samples.h). Field for
// field, no arithmetic: sample -> message -> sample reproduces every value bit for bit, so a lockstep DDS run sees
// exactly what the in-process closed loop sees. Shared by the agent node (inputs in, commands out) and the sim node
// (the reverse).

#include <cstdint>

#include <swa/msg/Detections.h>
#include <swa/msg/GnssFix.h>
#include <swa/msg/Imu.h>
#include <swa/msg/MessageHeader.h>
#include <swa/msg/VelocitySetpoint.h>

#include "swa/agent/samples.h"

namespace swa::wire {

msg::MessageHeader header(agent::StampNs stamp_ns, std::uint32_t seq);

agent::ImuSample fromMsg(const msg::Imu& m);
agent::DetectionSet fromMsg(const msg::Detections& m);
agent::GnssSample fromMsg(const msg::GnssFix& m);
agent::VelocityCommand fromMsg(const msg::VelocitySetpoint& m);  // seq = header.seq

msg::Imu toMsg(const agent::ImuSample& s, std::uint32_t uav_id, std::uint32_t seq);
msg::Detections toMsg(const agent::DetectionSet& s, std::uint32_t observer_id, std::uint32_t seq);
msg::GnssFix toMsg(const agent::GnssSample& s, std::uint32_t uav_id, std::uint32_t seq);
// `answered_seq`: header.seq of the IMU message the command answers.
msg::VelocitySetpoint toMsg(const agent::VelocityCommand& c, std::uint32_t uav_id, std::uint32_t seq,
                            std::uint32_t answered_seq);

}  // namespace swa::wire
