#include "recording_taps.h"

namespace swa::recording {
namespace {

// The reader profiles match each topic's writer (deploy/dds/profiles.xml): reliable, and transient local where the
// writer keeps history, so a recorder that starts late still gets what its writers kept.
template <class PubSubType>
dds::Reader<dds::Payload> tap(dds::Participant& p, Recording& recording, const std::string& topic,
                              const char* profile) {
  const std::uint16_t channel = recordingChannel<PubSubType>(recording, p, topic);
  return p.rawReader<PubSubType>(topic, profile, [&recording, channel](dds::RawSample&& s) {
    recording.writeCdr(channel, s.payload, s.source_time_ns);
  });
}

struct TapInto {
  dds::Participant& participant;
  Recording& recording;
  dds::Reader<dds::Payload> last;  // the last tapped: cmd_vel (forEachUavTap)

  template <class PubSubType>
  void operator()(const std::string& topic, const char* profile) {
    last = tap<PubSubType>(participant, recording, topic, profile);
  }
};

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

dds::Reader<dds::Payload> tapUavTopics(dds::Participant& participant, Recording& recording, int uav) {
  TapInto visitor{participant, recording, {}};
  forEachUavTap(uav, visitor);
  return visitor.last;
}

void tapClock(dds::Participant& participant, Recording& recording) {
  tap<msg::ClockPubSubType>(participant, recording, dds::topics::kClock, kClockProfile);
}

}  // namespace swa::recording
