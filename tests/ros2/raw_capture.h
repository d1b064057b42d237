#pragma once
// Readers that keep the serialized payloads of a topic exactly as they came off the wire (CDR encapsulation header
// included), under any type name: a TopicDataType whose "sample" is the payload's bytes. For checking what SWA's
// processes send against an independent decoder (tests/ros2/decode_check.mjs) and against the names a type must have.

#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "swa/dds/deployment.h"
#include "swa/dds/options.h"
#include "swa/dds/participant.h"
#include "swa/dds/raw_type.h"

namespace swa::testing::ros2 {

namespace fdds = eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::SerializedPayload_t;
using eprosima::fastrtps::types::ReturnCode_t;

using Bytes = std::vector<std::uint8_t>;

// Payloads of any size a test sends.
constexpr std::uint32_t kMaxPayload = 1u << 16;

// Up to the first `keep_first` and the last `keep_last` payloads of each topic.
class RawCapture {
 public:
  // A participant from SWA's profile (the environment's transport and swarm partition, as every SWA process).
  RawCapture(int domain, std::size_t keep_first, std::size_t keep_last) : first_(keep_first), last_(keep_last) {
    auto* factory = fdds::DomainParticipantFactory::get_instance();
    const std::string profiles = dds::resolveProfilesFile();
    if (factory->load_XML_profiles_file(profiles) != ReturnCode_t::RETCODE_OK) {
      throw dds::DdsError("cannot load " + profiles);
    }
    const dds::Deployment deployment = dds::resolveDeployment();
    fdds::DomainParticipantQos qos;
    if (factory->get_participant_qos_from_profile(dds::participantProfile(deployment.transport), qos) !=
        ReturnCode_t::RETCODE_OK) {
      throw dds::DdsError("no participant profile in " + profiles);
    }
    qos.name("swa_test_raw_capture");
    participant_ = factory->create_participant(static_cast<fdds::DomainId_t>(domain), qos);
    if (participant_ == nullptr) throw dds::DdsError("cannot create the capture participant");
    fdds::SubscriberQos sub_qos = fdds::SUBSCRIBER_QOS_DEFAULT;
    if (!deployment.swarm.empty()) sub_qos.partition().push_back(dds::swarmPartition(deployment.swarm).c_str());
    subscriber_ = participant_->create_subscriber(sub_qos);
  }
  ~RawCapture() {
    participant_->delete_contained_entities();
    fdds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
  }
  RawCapture(const RawCapture&) = delete;
  RawCapture& operator=(const RawCapture&) = delete;

  // A reader of DDS topic `topic` announcing DDS type `type`: RELIABLE and, for writers that keep history
  // (`transient_local`), TRANSIENT_LOCAL, so it also receives what was written before it matched (a TRANSIENT_LOCAL
  // reader does not match a VOLATILE writer).
  void read(const std::string& topic, const std::string& type, bool transient_local) {
    fdds::TypeSupport support(new dds::RawType(type, kMaxPayload));
    if (participant_->find_type(type).empty()) support.register_type(participant_);
    fdds::Topic* t = participant_->create_topic(topic, type, fdds::TOPIC_QOS_DEFAULT);
    if (t == nullptr) throw dds::DdsError("cannot create topic " + topic);
    fdds::DataReaderQos qos = fdds::DATAREADER_QOS_DEFAULT;
    qos.reliability().kind = fdds::RELIABLE_RELIABILITY_QOS;
    qos.durability().kind = transient_local ? fdds::TRANSIENT_LOCAL_DURABILITY_QOS : fdds::VOLATILE_DURABILITY_QOS;
    qos.history().kind = fdds::KEEP_LAST_HISTORY_QOS;
    qos.history().depth = 16;
    listeners_.push_back(std::make_unique<Listener>(*this, topic));
    if (subscriber_->create_datareader(t, qos, listeners_.back().get()) == nullptr) {
      throw dds::DdsError("cannot create a reader on " + topic);
    }
  }

  // Payloads by DDS topic, in arrival order (the first ones, then the last ones).
  std::map<std::string, std::vector<Bytes>> payloads() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    std::map<std::string, std::vector<Bytes>> out;
    for (const auto& [topic, kept] : kept_) {
      std::vector<Bytes>& v = out[topic];
      v = kept.first;
      v.insert(v.end(), kept.last.begin(), kept.last.end());
    }
    return out;
  }

 private:
  struct Kept {
    std::vector<Bytes> first, last;
  };
  class Listener : public fdds::DataReaderListener {
   public:
    Listener(RawCapture& owner, std::string topic) : owner_(owner), topic_(std::move(topic)) {}
    void on_data_available(fdds::DataReader* reader) override {
      Bytes sample;
      fdds::SampleInfo info;
      while (reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
        if (info.valid_data) owner_.keep(topic_, std::move(sample));
        sample.clear();
      }
    }

   private:
    RawCapture& owner_;
    std::string topic_;
  };

  void keep(const std::string& topic, Bytes&& b) {
    const std::lock_guard<std::mutex> lock(mutex_);
    Kept& k = kept_[topic];
    if (k.first.size() < first_) {
      k.first.push_back(std::move(b));
      return;
    }
    if (last_ == 0) return;
    if (k.last.size() == last_) k.last.erase(k.last.begin());
    k.last.push_back(std::move(b));
  }

  const std::size_t first_, last_;
  mutable std::mutex mutex_;
  std::map<std::string, Kept> kept_;
  std::vector<std::unique_ptr<Listener>> listeners_;  // outlive the readers (deleted with the participant first)
  fdds::DomainParticipant* participant_ = nullptr;
  fdds::Subscriber* subscriber_ = nullptr;
};

// The message of `payload` decoded by the generated code of PubSubType; false if it does not decode.
template <class PubSubType>
bool decode(const Bytes& payload, typename PubSubType::type& out) {
  return dds::decodePayload<PubSubType>(payload, out);
}

// The payload a DataWriter of PubSubType sends for `m`.
template <class PubSubType>
Bytes encode(typename PubSubType::type m) {
  PubSubType type;
  SerializedPayload_t p(type.getSerializedSizeProvider(&m)());
  if (!type.serialize(&m, &p)) return {};
  return Bytes(p.data, p.data + p.length);
}

}  // namespace swa::testing::ros2
