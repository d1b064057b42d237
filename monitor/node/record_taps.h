#pragma once
// The DDS side of a recording (swa_monitor --record): raw readers whose payloads go into the MCAP file unchanged.
// The monitor's own inputs (truth, events, states) are read raw anyway (monitor_node.cpp) and recorded there; these
// are the topics the monitor reads only to record them.

#include <cstdint>
#include <string>

#include "swa/dds/participant.h"
#include "swa/record/recording.h"

namespace swa::monitor_node {

// The recording's topic for an SWA topic: the ROS 2 topic it is on the wire in the ros2 naming (with its namespace),
// else "/" + the SWA name; either way what `ros2 topic echo` or a viewer shows, e.g. /swa/uav0/imu.
std::string recordedTopic(const dds::WireNames& names, const std::string& swa_topic);

// The swa_msgs name of a generated type ("swa::msg::Imu" -> "Imu").
std::string msgTypeName(const std::string& generated);

// The recording channel of `swa_topic` read by `participant` with PubSubType.
template <class PubSubType>
std::uint16_t recordingChannel(record::Recording& recording, const dds::Participant& participant,
                               const std::string& swa_topic) {
  PubSubType type;
  return recording.cdrChannel(recordedTopic(participant.wireNames(), swa_topic), msgTypeName(type.getName()));
}

// Readers of UAV `uav`'s detections, imu, gnss, cmd_vel and bridge_state into `recording` (which must outlive the
// participant's readers). Returns the cmd_vel reader: its writer keeps only the newest command (KEEP_LAST 1), so a
// recorder that matches it after the run started misses the commands before; the monitor waits for it to match
// before it lets the simulator start (monitor_node.cpp). The sensors' writers keep 1000 samples for late readers.
dds::Reader<dds::Payload> tapUavTopics(dds::Participant& participant, record::Recording& recording, int uav);
// A reader of swa/clock into `recording`.
void tapClock(dds::Participant& participant, record::Recording& recording);

}  // namespace swa::monitor_node
