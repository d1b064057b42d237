#pragma once
// RAII Fast DDS participant with typed writer / reader helpers, shared by every SWA node.
//
//   swa::dds::Participant p("swa_agent_3", domain, swa::dds::resolveProfilesFile());
//   auto cmd = p.writer<swa::msg::VelocitySetpointPubSubType>(topics::cmdVel(3), qos::kCommandWriter);
//   auto imu = p.reader<swa::msg::ImuPubSubType>(topics::imu(3), qos::kSensorReader,
//                                                [&](swa::msg::Imu&& m) { queue.push(std::move(m)); });
//
// QoS comes only from the XML profiles (idl/runtime/dds/profiles.xml, loaded before anything else); the code names a
// profile per endpoint and never sets QoS itself. Writer / Reader are non-owning handles, valid while their
// Participant lives. The participant owns one publisher, one subscriber, the topics, and the reader listeners; its
// destructor deletes every entity (so no /dev/shm segment survives a clean exit) and only then the listeners.
// Before deleting, it waits (at most kShutdownAckWaitS) until every writer is acknowledged by its matched readers or
// the dead ones among them are forgotten (participant lease): Fast DDS 2.9 can hang deleting a reliable writer
// while it is heartbeating a reader that never answers. A destruction that outlasts kDeletionLimitS ends the process.
//
// Threading: a reader's callback runs on a Fast DDS thread. Keep it to a push into a SampleQueue, and let whatever
// it captures outlive the Participant.
//
// Where each job is: Writer / Reader and the sample listeners in endpoints.h (src/endpoints.cpp); creation from the
// profiles, topics and endpoints in src/participant.cpp; the shutdown in src/participant_shutdown.cpp; discovery and
// the peers in src/peer_listener.h / .cpp; the shared-memory ports in shm_ports.h.

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TopicDataType.hpp>

#include "swa/dds/endpoints.h"
#include "swa/dds/naming.h"
#include "swa/dds/peer_book.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/raw_type.h"
#include "swa/dds/shm_ports.h"

namespace swa::dds {

class DdsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Longest wait for outstanding acknowledgments on destruction: above the profile's 4 s participant lease.
constexpr double kShutdownAckWaitS = 6.0;
// Longest the whole destruction may take, acknowledgments included; beyond it Fast DDS is stuck inside the
// participant (participant_shutdown.cpp) and the process exits with kExitParticipantStuck, for its supervisor
// (swa_launch, a container's restart policy) to restart it.
constexpr double kDeletionLimitS = kShutdownAckWaitS + 6.0;
constexpr int kExitParticipantStuck = 70;  // EX_SOFTWARE (sysexits.h): an internal error

class Participant {
 public:
  // Loads `profiles_file` (once per process; a second Participant must name the same file), then creates the
  // participant `name` on `domain_id` from the profile qos::kParticipant. Throws DdsError with a readable reason.
  Participant(const std::string& name, int domain_id, const std::string& profiles_file);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  // Topics are named as SWA names them (swa/dds/topics.h); on the wire they carry the names of SWA_NAMING (naming.h).
  // A writer on `topic_name` (created on first use, type registered on first use) with the QoS of the XML
  // data_writer profile `profile`. Throws DdsError.
  template <class PubSubType>
  Writer<typename PubSubType::type> writer(const std::string& topic_name, const std::string& profile) {
    eprosima::fastdds::dds::DataWriter* w = createWriter(topic(topic_name, new PubSubType()), profile);
    writers_.push_back(w);
    return Writer<typename PubSubType::type>(w);
  }

  // A reader whose every valid sample is handed to `on_sample` on a middleware thread.
  template <class PubSubType>
  Reader<typename PubSubType::type> reader(const std::string& topic_name, const std::string& profile,
                                           std::function<void(typename PubSubType::type&&)> on_sample) {
    using Msg = typename PubSubType::type;
    return readerWithOrigin<PubSubType>(topic_name, profile,
                                        [f = std::move(on_sample)](Msg&& m, const WriterGuid&) { f(std::move(m)); });
  }

  // The same, with the GUID of the writer each sample came from.
  template <class PubSubType>
  Reader<typename PubSubType::type> readerWithOrigin(
      const std::string& topic_name, const std::string& profile,
      std::function<void(typename PubSubType::type&&, const WriterGuid&)> on_sample) {
    using Msg = typename PubSubType::type;
    return Reader<Msg>(createReader(topic(topic_name, new PubSubType()), profile,
                                    std::make_unique<detail::CallbackListener<Msg>>(std::move(on_sample))));
  }

  // The same, with each sample's identities (a ROS 2 service's requests or replies).
  template <class PubSubType>
  Reader<typename PubSubType::type> readerWithIds(
      const std::string& topic_name, const std::string& profile,
      std::function<void(typename PubSubType::type&&, const SampleIds&)> on_sample) {
    using Msg = typename PubSubType::type;
    return Reader<Msg>(createReader(topic(topic_name, new PubSubType()), profile,
                                    std::make_unique<detail::IdentityListener<Msg>>(std::move(on_sample))));
  }

  // A writer of ready-made payloads on `topic_name`, announced as PubSubType (a replay's: raw_type.h). Same rule.
  template <class PubSubType>
  Writer<Payload> rawWriter(const std::string& topic_name, const std::string& profile) {
    eprosima::fastdds::dds::DataWriter* w = createWriter(topic(topic_name, rawTypeOf<PubSubType>()), profile);
    writers_.push_back(w);
    return Writer<Payload>(w);
  }

  // A reader of the payloads of `topic_name` as PubSubType's writers send them, undecoded (raw_type.h): for a
  // recording, and for a node that also keeps the bytes of what it decodes. In one participant a type name stands for
  // one TypeSupport, so a topic read raw here must not also be read or written typed by the same participant.
  template <class PubSubType>
  Reader<Payload> rawReader(const std::string& topic_name, const std::string& profile,
                            std::function<void(RawSample&&)> on_sample) {
    return Reader<Payload>(createReader(topic(topic_name, rawTypeOf<PubSubType>()), profile,
                                        std::make_unique<detail::RawListener>(std::move(on_sample))));
  }

  const std::string& name() const { return name_; }
  int domainId() const { return domain_id_; }
  // How this participant names topics and types on the wire (SWA_NAMING, naming.h).
  const WireNames& wireNames() const { return names_; }

  // Discovery (peer_book.h). The oldest live participant with our name in our swarm, if any; whether one of them is
  // older than us (we must give way); how many peers came back after their lease had expired, and the last one's name.
  std::optional<Peer> twin() const;
  bool mustGiveWay() const;
  // Younger twins discovered since the last call, gone again or not (PeerBook::takeYoungerTwins).
  std::vector<Peer> takeYoungerTwins();
  struct PeersBack {
    int count = 0;
    std::string last_name;
    PeerKey last_key{};
  };
  PeersBack peersBackAfterLease() const;
  // Participants that left since the last call (PeerBook::takeGone).
  std::vector<PeerKey> takePeersGone();
  // Whether a reader of participant `peer` is matched with `w` (as this side's discovery sees it).
  template <class Msg>
  bool readBy(const Writer<Msg>& w, const PeerKey& peer) const {
    return writerReadBy(w.writer_, peer);
  }

  // The shared-memory ports this process listens on as their only reader (its participants' unicast ports), and those
  // of them that Fast DDS re-created under it, so that what peers send to them is lost (shm_ports.h). Linux; empty
  // without shared memory.
  static std::vector<int> ownSharedMemoryPorts() { return dds::ownSharedMemoryPorts(); }
  static std::vector<int> deafSharedMemoryPorts() { return dds::deafSharedMemoryPorts(); }

  // When this participant last authenticated a remote one (DDS Security); the clock's epoch if never or without
  // security. A secured start whose handshakes still complete is slow, not stalled (handshake_watch.h).
  std::chrono::steady_clock::time_point lastAuthentication() const;

  // The destructor then deletes at once instead of waiting for the readers' acknowledgments: a participant that no
  // longer hears its port (above) would wait the whole kShutdownAckWaitS for acknowledgments that cannot reach it.
  void abandonAcknowledgments() { abandon_acknowledgments_ = true; }

 private:
  // Takes ownership of `type`.
  eprosima::fastdds::dds::Topic* topic(const std::string& topic_name, eprosima::fastdds::dds::TopicDataType* type);
  // Deleted after the participant (the destructor deletes the participant explicitly). Defined in src/peer_listener.h.
  class PeerListener;
  std::unique_ptr<PeerListener> peer_listener_;
  bool writerReadBy(const eprosima::fastdds::dds::DataWriter* w, const PeerKey& peer) const;
  eprosima::fastdds::dds::DataWriter* createWriter(eprosima::fastdds::dds::Topic* topic, const std::string& profile);
  // A reader of `topic` whose samples go to `listener`, which is kept here for as long as the participant lives.
  eprosima::fastdds::dds::DataReader* createReader(
      eprosima::fastdds::dds::Topic* topic, const std::string& profile,
      std::unique_ptr<eprosima::fastdds::dds::DataReaderListener> listener);

  // Declared first, destroyed last: the listeners outlive the readers that call them.
  std::vector<std::unique_ptr<eprosima::fastdds::dds::DataReaderListener>> listeners_;
  std::string name_;
  int domain_id_ = 0;
  WireNames names_;
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::map<std::string, eprosima::fastdds::dds::Topic*> topics_;
  std::vector<eprosima::fastdds::dds::DataWriter*> writers_;
  bool abandon_acknowledgments_ = false;
};

}  // namespace swa::dds
