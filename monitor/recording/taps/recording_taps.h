#pragma once
// The DDS side of a recording (swa_monitor --record): raw readers whose payloads go into the MCAP file unchanged, and
// the list of what a complete recording holds. The monitor's own inputs (truth, events, states) are read raw anyway
// (monitor/node/monitor_node.cpp) and recorded there; these are the topics the monitor reads only to record them.
// The recording's one DDS part: the file itself (swa/recording/) knows no DDS.

#include <cstdint>
#include <string>

#include <swa/msg/AgentStatePubSubTypes.h>
#include <swa/msg/BridgeStatePubSubTypes.h>
#include <swa/msg/ClockPubSubTypes.h>
#include <swa/msg/DetectionsPubSubTypes.h>
#include <swa/msg/GnssFixPubSubTypes.h>
#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/ScenarioEventPubSubTypes.h>
#include <swa/msg/SensorFramePubSubTypes.h>
#include <swa/msg/SwarmTruthPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>

#include "swa/dds/participant.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"
#include "swa/recording/recording.h"

namespace swa::recording {

// The recording's topic for an SWA topic: the ROS 2 topic it is on the wire in the ros2 naming (with its namespace),
// else "/" + the SWA name; either way what `ros2 topic echo` or a viewer shows, e.g. /swa/uav0/imu.
std::string recordedTopic(const dds::WireNames& names, const std::string& swa_topic);

// The swa_msgs name of a generated type ("swa::msg::Imu" -> "Imu").
std::string msgTypeName(const std::string& generated);

// The recording channel of `swa_topic` read by `participant` with PubSubType.
template <class PubSubType>
std::uint16_t recordingChannel(Recording& recording, const dds::Participant& participant,
                               const std::string& swa_topic) {
  PubSubType type;
  return recording.cdrChannel(recordedTopic(participant.wireNames(), swa_topic), msgTypeName(type.getName()));
}

// The reader profiles of the monitor's own inputs (idl/runtime/dds/profiles.xml), named once for the monitor and for
// the bare-reader baseline of tests/bench/bench_record_reader.cpp.

// The topics the monitor reads only to record them, per UAV, each with the reader profile matching its writer:
// `visit.template operator()<PubSubType>(swa_topic, profile)`. cmd_vel comes last.
template <class Visit>
void forEachUavTap(int uav, Visit&& visit);

// Every topic of a complete recording (RecordSet::kAll) of UAVs 0..uav_count-1 with the profile the monitor reads it
// with: truth, events, clock, and per UAV its state and forEachUavTap. Same visitor as above.
template <class Visit>
void forEachRecordedTopic(int uav_count, Visit&& visit);

// The readers a recorder waits for before it lets the simulator start (monitor_node.cpp): samples a writer sent
// before the recorder's reader had matched it are not all repaired. cmd_vel's writer keeps only the newest command
// (KEEP_LAST 1); the sensors' writers keep 1000 samples, but a burst of them at once overflows the reader's depth.
// The sensors come either as frames (swa/uav<i>/sensors, from the simulator) or one by one (swa/uav<i>/imu, from the
// simulator or an autopilot bridge): one of the two matched is enough.
struct UavTaps {
  dds::Reader<dds::Payload> commands;
  dds::Reader<dds::Payload> imu;
  dds::Reader<dds::Payload> frames;
  bool matched() const { return commands.matched() > 0 && (imu.matched() > 0 || frames.matched() > 0); }
};

// Readers of UAV `uav`'s detections, imu, gnss, sensors (split into the first three), cmd_vel and bridge_state into
// `recording` (which must outlive the participant's readers).
UavTaps tapUavTopics(dds::Participant& participant, Recording& recording, int uav);
// A reader of swa/clock into `recording`.
void tapClock(dds::Participant& participant, Recording& recording);

template <class Visit>
void forEachUavTap(int uav, Visit&& visit) {
  namespace topics = dds::topics;
  visit.template operator()<msg::DetectionsPubSubType>(topics::detections(uav), dds::qos::kDetectionsGnssReader);
  visit.template operator()<msg::ImuPubSubType>(topics::imu(uav), dds::qos::kSensorReader);
  visit.template operator()<msg::GnssFixPubSubType>(topics::gnss(uav), dds::qos::kDetectionsGnssReader);
  // The simulator's frames (SWA naming): the recorder files each part under its own topic (recording_taps.cpp).
  visit.template operator()<msg::SensorFramePubSubType>(topics::sensors(uav), dds::qos::kFrameReader);
  visit.template operator()<msg::BridgeStatePubSubType>(topics::bridgeState(uav), dds::qos::kStateReader);
  visit.template operator()<msg::VelocitySetpointPubSubType>(topics::cmdVel(uav), dds::qos::kCommandReader);
}

template <class Visit>
void forEachRecordedTopic(int uav_count, Visit&& visit) {
  visit.template operator()<msg::SwarmTruthPubSubType>(dds::topics::kTruth, dds::qos::kTruthReader);
  visit.template operator()<msg::ScenarioEventPubSubType>(dds::topics::kEvents, dds::qos::kEventReader);
  visit.template operator()<msg::ClockPubSubType>(dds::topics::kClock, dds::qos::kClockReader);
  for (int uav = 0; uav < uav_count; ++uav) {
    visit.template operator()<msg::AgentStatePubSubType>(dds::topics::state(uav), dds::qos::kStateReader);
    forEachUavTap(uav, visit);
  }
}

}  // namespace swa::recording
