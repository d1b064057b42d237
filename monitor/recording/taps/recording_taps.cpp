#include "recording_taps.h"

#include <type_traits>

#include "swa/dds/qos_profiles.h"
#include "swa/dds/raw_type.h"

namespace swa::recording {
namespace {

// The reader profiles match each topic's writer (idl/runtime/dds/profiles.xml): reliable, and transient local where
// the writer keeps history, so a recorder that starts late still gets what its writers kept.
// Every tap records a sample once: a tap created again with the participant is sent its writers' history once more
// (Recording::firstDelivery), keyed by the channel it writes (a frame tap: its IMU channel).
bool firstDelivery(Recording& recording, std::uint16_t channel, const dds::RawSample& s) {
  return recording.firstDelivery(channel, s.id.writer, s.id.seq);
}

template <class PubSubType>
dds::Reader<dds::Payload> tap(dds::Participant& p, Recording& recording, const std::string& topic,
                              const char* profile) {
  const std::uint16_t channel = recordingChannel<PubSubType>(recording, p, topic);
  return p.rawReader<PubSubType>(topic, profile, [&recording, channel](dds::RawSample&& s) {
    if (firstDelivery(recording, channel, s)) recording.writeCdr(channel, s.payload, s.source_time_ns);
  });
}

// A frame's parts go to the channels of their own topics (swa/uav<i>/imu, detections, gnss), each as the bytes its
// own topic would carry: a recording, and its replay, are the same whether the simulator wrote frames or separate
// topics. A frame that does not decode is kept as it came, on its own topic.
dds::Reader<dds::Payload> tapFrames(dds::Participant& p, Recording& recording, const std::string& topic,
                                    const char* profile) {
  const std::string uav_prefix = topic.substr(0, topic.rfind('/') + 1);
  const std::uint16_t imu = recordingChannel<msg::ImuPubSubType>(recording, p, uav_prefix + "imu");
  const std::uint16_t det = recordingChannel<msg::DetectionsPubSubType>(recording, p, uav_prefix + "detections");
  const std::uint16_t gnss = recordingChannel<msg::GnssFixPubSubType>(recording, p, uav_prefix + "gnss");
  const std::string frame_topic = recordedTopic(p.wireNames(), topic);
  return p.rawReader<msg::SensorFramePubSubType>(
      topic, profile, [&recording, imu, det, gnss, frame_topic](dds::RawSample&& s) {
        if (!firstDelivery(recording, imu, s)) return;
        msg::SensorFrame f;
        if (!dds::decodePayload<msg::SensorFramePubSubType>(s.payload, f)) {
          msg::SensorFramePubSubType type;
          recording.writeCdr(recording.cdrChannel(frame_topic, msgTypeName(type.getName())), s.payload,
                             s.source_time_ns);
          return;
        }
        for (const msg::Detections& d : f.detection_set()) {
          recording.writeCdr(det, dds::encodePayload<msg::DetectionsPubSubType>(d), s.source_time_ns);
        }
        for (const msg::GnssFix& g : f.gnss_fix()) {
          recording.writeCdr(gnss, dds::encodePayload<msg::GnssFixPubSubType>(g), s.source_time_ns);
        }
        for (const msg::Imu& i : f.imu_sample()) {
          recording.writeCdr(imu, dds::encodePayload<msg::ImuPubSubType>(i), s.source_time_ns);
        }
      });
}

struct TapInto {
  dds::Participant& participant;
  Recording& recording;
  UavTaps taps;

  template <class PubSubType>
  void operator()(const std::string& topic, const char* profile) {
    if constexpr (std::is_same_v<PubSubType, msg::SensorFramePubSubType>) {
      taps.frames = tapFrames(participant, recording, topic, profile);
    } else if constexpr (std::is_same_v<PubSubType, msg::ImuPubSubType>) {
      taps.imu = tap<PubSubType>(participant, recording, topic, profile);
    } else if constexpr (std::is_same_v<PubSubType, msg::VelocitySetpointPubSubType>) {
      taps.commands = tap<PubSubType>(participant, recording, topic, profile);
    } else {
      tap<PubSubType>(participant, recording, topic, profile);
    }
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

UavTaps tapUavTopics(dds::Participant& participant, Recording& recording, int uav) {
  TapInto visitor{participant, recording, {}};
  forEachUavTap(uav, visitor);
  return visitor.taps;
}

void tapClock(dds::Participant& participant, Recording& recording) {
  tap<msg::ClockPubSubType>(participant, recording, dds::topics::kClock, dds::qos::kClockReader);
}

}  // namespace swa::recording
