#include "record_taps.h"

#include <swa/msg/BridgeStatePubSubTypes.h>
#include <swa/msg/ClockPubSubTypes.h>
#include <swa/msg/DetectionsPubSubTypes.h>
#include <swa/msg/GnssFixPubSubTypes.h>
#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>

#include "swa/dds/topics.h"

namespace swa::monitor_node {
namespace {

// The reader profiles match each topic's writer (deploy/dds/profiles.xml): reliable, and transient local where the
// writer keeps history, so a recorder that starts late still gets what its writers kept.
template <class PubSubType>
dds::Reader<dds::Payload> tap(dds::Participant& p, record::Recording& recording, const std::string& topic,
                              const char* profile) {
  const std::uint16_t channel = recordingChannel<PubSubType>(recording, p, topic);
  return p.rawReader<PubSubType>(topic, profile, [&recording, channel](dds::RawSample&& s) {
    recording.writeCdr(channel, s.payload, s.source_time_ns);
  });
}

}  // namespace

std::string recordedTopic(const dds::WireNames& names, const std::string& swa_topic) {
  if (names.naming == dds::Naming::kRos2) {
    if (auto ros = dds::rosTopicOf(dds::ddsTopic(names, swa_topic))) return *ros;
  }
  return "/" + swa_topic;
}

std::string msgTypeName(const std::string& generated) {
  const std::size_t colon = generated.rfind("::");
  return colon == std::string::npos ? generated : generated.substr(colon + 2);
}

dds::Reader<dds::Payload> tapUavTopics(dds::Participant& participant, record::Recording& recording, int uav) {
  namespace topics = dds::topics;
  tap<msg::DetectionsPubSubType>(participant, recording, topics::detections(uav), "swa_detections_gnss_reader");
  tap<msg::ImuPubSubType>(participant, recording, topics::imu(uav), "swa_sensor_reader");
  tap<msg::GnssFixPubSubType>(participant, recording, topics::gnss(uav), "swa_detections_gnss_reader");
  tap<msg::BridgeStatePubSubType>(participant, recording, topics::bridgeState(uav), "swa_state_reader");
  return tap<msg::VelocitySetpointPubSubType>(participant, recording, topics::cmdVel(uav), "swa_command_reader");
}

void tapClock(dds::Participant& participant, record::Recording& recording) {
  tap<msg::ClockPubSubType>(participant, recording, dds::topics::kClock, "swa_clock_reader");
}

}  // namespace swa::monitor_node
