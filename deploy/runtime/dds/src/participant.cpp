#include "swa/dds/participant.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastdds/rtps/common/WriteParams.h>
#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>
#include <fastdds/dds/core/status/SubscriptionMatchedStatus.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "participant_qos.h"
#include "swa/dds/deployment.h"
#include "swa/dds/participant_id.h"
#include "swa/dds/security_check.h"
#include "swa/dds/shm_ports.h"

namespace swa::dds {

namespace fdds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;

namespace detail {

int publicationMatched(fdds::DataWriter* writer) {
  fdds::PublicationMatchedStatus status;
  if (writer == nullptr || writer->get_publication_matched_status(status) != ReturnCode_t::RETCODE_OK) return 0;
  return status.current_count;
}

int subscriptionMatched(fdds::DataReader* reader) {
  fdds::SubscriptionMatchedStatus status;
  if (reader == nullptr || reader->get_subscription_matched_status(status) != ReturnCode_t::RETCODE_OK) return 0;
  return status.current_count;
}

bool waitForAcknowledgments(fdds::DataWriter* writer, double seconds) {
  if (writer == nullptr) return false;
  return writer->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(seconds)) == ReturnCode_t::RETCODE_OK;
}

namespace {

Guid guidOf(const eprosima::fastrtps::rtps::GUID_t& g) {
  Guid out{};
  std::copy(g.guidPrefix.value, g.guidPrefix.value + 12, out.begin());
  std::copy(g.entityId.value, g.entityId.value + 4, out.begin() + 12);
  return out;
}

eprosima::fastrtps::rtps::GUID_t fastGuidOf(const Guid& g) {
  eprosima::fastrtps::rtps::GUID_t out;
  std::copy(g.begin(), g.begin() + 12, out.guidPrefix.value);
  std::copy(g.begin() + 12, g.end(), out.entityId.value);
  return out;
}

SampleId sampleIdOf(const eprosima::fastrtps::rtps::SampleIdentity& id) {
  return SampleId{guidOf(id.writer_guid()), static_cast<std::int64_t>(id.sequence_number().to64long())};
}

eprosima::fastrtps::rtps::SampleIdentity fastSampleIdOf(const SampleId& id) {
  eprosima::fastrtps::rtps::SampleIdentity out;
  out.writer_guid(fastGuidOf(id.writer));
  out.sequence_number(eprosima::fastrtps::rtps::SequenceNumber_t(static_cast<std::uint64_t>(id.seq)));
  return out;
}

}  // namespace

bool writeRelated(fdds::DataWriter* writer, void* data, const SampleId* related, const Guid* reply_reader,
                  SampleId* written) {
  if (writer == nullptr) return false;
  eprosima::fastrtps::rtps::WriteParams params;
  if (related != nullptr) params.related_sample_identity(fastSampleIdOf(*related));
  if (reply_reader != nullptr) params.related_sample_identity().writer_guid(fastGuidOf(*reply_reader));
  if (!writer->write(data, params)) return false;
  if (written != nullptr) *written = sampleIdOf(params.sample_identity());
  return true;
}

Guid readerGuid(const fdds::DataReader* reader) { return reader == nullptr ? Guid{} : guidOf(reader->guid()); }

SampleIds sampleIdsOf(const fdds::SampleInfo& info) {
  return SampleIds{sampleIdOf(info.sample_identity), sampleIdOf(info.related_sample_identity)};
}

}  // namespace detail

namespace {

PeerKey keyOf(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix) {
  PeerKey key{};
  std::copy(prefix.value, prefix.value + key.size(), key.begin());
  return key;
}

}  // namespace

// Feeds the participant's PeerBook from discovery (peer_book.h). With SWA_DDS_TRACE=1 also one line on stderr per
// remote participant discovered / lost / authenticated, to see on a real network (or with DDS Security) who found
// whom. Only participant events: the data callbacks stay with the readers.
class Participant::PeerListener : public fdds::DomainParticipantListener {
 public:
  PeerListener(std::string self, PeerCard card, bool trace)
      : self_(self), book_(std::move(self), std::move(card)), trace_(trace) {}

  void on_participant_discovery(fdds::DomainParticipant*,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override {
    using Status = eprosima::fastrtps::rtps::ParticipantDiscoveryInfo::DISCOVERY_STATUS;
    const PeerKey key = keyOf(info.info.m_guid.guidPrefix);
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (info.status == Status::DISCOVERED_PARTICIPANT || info.status == Status::CHANGED_QOS_PARTICIPANT) {
        const auto& bytes = info.info.m_userData.data_vec();
        book_.discovered(Peer{key, info.info.m_participantName.to_string(),
                              decodePeerCard(std::string(bytes.begin(), bytes.end()))});
      } else if (info.status == Status::REMOVED_PARTICIPANT || info.status == Status::DROPPED_PARTICIPANT) {
        book_.lost(key, info.status == Status::DROPPED_PARTICIPANT);
      }
    }
    if (!trace_ || info.status == Status::CHANGED_QOS_PARTICIPANT) return;
    const char* what = info.status == Status::DISCOVERED_PARTICIPANT ? "discovered"
                       : info.status == Status::REMOVED_PARTICIPANT  ? "removed"
                       : info.status == Status::DROPPED_PARTICIPANT  ? "dropped (lease expired)"
                                                                     : "ignored";
    std::ostringstream guid;
    guid << info.info.m_guid;
    std::fprintf(stderr, "%s: [dds trace] participant %s %s (%s)\n", self_.c_str(), info.info.m_participantName.c_str(),
                 what, guid.str().c_str());
  }

#if HAVE_SECURITY
  void onParticipantAuthentication(fdds::DomainParticipant*,
                                   eprosima::fastrtps::rtps::ParticipantAuthenticationInfo&& info) override {
    if (info.status == eprosima::fastrtps::rtps::ParticipantAuthenticationInfo::AUTHORIZED_PARTICIPANT) {
      last_authentication_ns_ = std::chrono::steady_clock::now().time_since_epoch().count();
    }
    if (!trace_) return;
    std::ostringstream guid;
    guid << info.guid;
    std::fprintf(stderr, "%s: [dds trace] participant %s %s\n", self_.c_str(), guid.str().c_str(),
                 info.status == eprosima::fastrtps::rtps::ParticipantAuthenticationInfo::AUTHORIZED_PARTICIPANT
                     ? "authenticated"
                     : "REFUSED by authentication");
  }
#endif

  // Which participants read each of our writers: a matched reader's handle is its GUID, whose first 12 bytes are
  // its participant's prefix.
  void on_publication_matched(fdds::DataWriter* writer, const fdds::PublicationMatchedStatus& status) override {
    PeerKey key{};
    for (std::size_t i = 0; i < key.size(); ++i) key[i] = status.last_subscription_handle.value[i];
    const std::lock_guard<std::mutex> lock(mutex_);
    std::multiset<PeerKey>& readers = readers_[writer];
    if (status.current_count_change > 0) {
      readers.insert(key);
    } else if (status.current_count_change < 0) {
      if (const auto it = readers.find(key); it != readers.end()) readers.erase(it);
    }
  }

  bool readBy(const fdds::DataWriter* writer, const PeerKey& peer) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = readers_.find(writer);
    return it != readers_.end() && it->second.count(peer) > 0;
  }

  std::chrono::steady_clock::time_point lastAuthentication() const {
    return std::chrono::steady_clock::time_point(std::chrono::steady_clock::duration(last_authentication_ns_.load()));
  }

  template <class F>
  auto withBook(F&& f) {
    const std::lock_guard<std::mutex> lock(mutex_);
    return f(book_);
  }

 private:
  std::string self_;
  std::mutex mutex_;
  PeerBook book_;
  bool trace_;
  std::atomic<std::chrono::steady_clock::rep> last_authentication_ns_{0};  // steady clock; 0: never
  std::map<const fdds::DataWriter*, std::multiset<PeerKey>> readers_;
};

namespace {

std::string readWhole(const char* path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

Participant::Participant(const std::string& name, int domain_id, const std::string& profiles_file)
    : name_(name), domain_id_(domain_id) {
  detail::loadProfilesOnce(profiles_file);
  Deployment deployment;
  try {
    deployment = resolveDeployment();
  } catch (const std::invalid_argument& e) {
    throw DdsError(e.what());
  }
  names_ = deployment.names;
  detail::ParticipantSetup setup = detail::participantSetup(name, domain_id, profiles_file, deployment);
  fdds::DomainParticipantQos& qos = setup.qos;
  const std::optional<SecurityFiles>& security = setup.security;
  auto* factory = fdds::DomainParticipantFactory::get_instance();
  const char* trace = std::getenv("SWA_DDS_TRACE");
  peer_listener_ = std::make_unique<PeerListener>(name, setup.card, trace != nullptr && std::string(trace) == "1");
  participant_ = factory->create_participant(static_cast<fdds::DomainId_t>(domain_id), qos, peer_listener_.get(),
                                             fdds::StatusMask::publication_matched());
  if (participant_ == nullptr) {
    if (security) {
      throw DdsError("DDS Security refused the credentials of participant '" + name + "' on domain " +
                     std::to_string(domain_id) + ": " + detail::refusalReason(*security));
    }
    throw DdsError("cannot create DDS participant '" + name + "' on domain " + std::to_string(domain_id) +
                   " (transport " + transportName(deployment.transport) + ")");
  }
  const PeerKey self_key = keyOf(participant_->guid().guidPrefix);
  peer_listener_->withBook([&](PeerBook& book) { book.setSelfKey(self_key); });
  // SWA_SWARM: every reader and writer of this process in the swarm's partition (deployment.h).
  fdds::PublisherQos publisher_qos = fdds::PUBLISHER_QOS_DEFAULT;
  fdds::SubscriberQos subscriber_qos = fdds::SUBSCRIBER_QOS_DEFAULT;
  if (!deployment.swarm.empty()) {
    publisher_qos.partition().push_back(swarmPartition(deployment.swarm).c_str());
    subscriber_qos.partition().push_back(swarmPartition(deployment.swarm).c_str());
  }
  publisher_ = participant_->create_publisher(publisher_qos);
  subscriber_ = participant_->create_subscriber(subscriber_qos);
  if (publisher_ == nullptr || subscriber_ == nullptr) {
    participant_->delete_contained_entities();
    factory->delete_participant(participant_);
    throw DdsError("cannot create publisher/subscriber for participant '" + name + "'");
  }
}

Participant::~Participant() {
  // See the header: no writer may still be heartbeating an unresponsive reader when it is deleted.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(kShutdownAckWaitS);
  for (fdds::DataWriter* w : abandon_acknowledgments_ ? std::vector<fdds::DataWriter*>() : writers_) {
    const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if (!detail::waitForAcknowledgments(w, std::max(left, 0.0))) {
      std::fprintf(stderr, "%s: writer on %s still unacknowledged after %.0f s; deleting anyway\n", name_.c_str(),
                   w->get_topic()->get_name().c_str(), kShutdownAckWaitS);
    }
  }
  // Then every entity (readers stop calling their listeners); the listeners die after this body.
  participant_->delete_contained_entities();
  fdds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

void detail::RawListener::on_data_available(fdds::DataReader* reader) {
  fdds::SampleInfo info;
  RawSample sample;
  while (reader->take_next_sample(&sample.payload, &info) == ReturnCode_t::RETCODE_OK) {
    if (info.valid_data) {
      sample.source_time_ns = info.source_timestamp.to_ns();
      on_sample_(std::move(sample));
    }
    sample = RawSample();
  }
}

fdds::Topic* Participant::topic(const std::string& topic_name, fdds::TopicDataType* type) {
  fdds::TypeSupport support(type);  // owns `type` from here on
  // The wire names of this naming (naming.h); the code and the logs keep SWA's.
  const std::string type_name = ddsType(names_, support.get_type_name());
  if (participant_->find_type(type_name).empty() &&
      support.register_type(participant_, type_name) != ReturnCode_t::RETCODE_OK) {
    throw DdsError("cannot register type " + type_name);
  }
  auto it = topics_.find(topic_name);
  if (it != topics_.end()) {
    if (it->second->get_type_name() != type_name) {
      throw DdsError("topic " + topic_name + " already exists with type " + it->second->get_type_name());
    }
    return it->second;
  }
  const std::string dds_name = ddsTopic(names_, topic_name);
  fdds::Topic* t = participant_->create_topic(dds_name, type_name, fdds::TOPIC_QOS_DEFAULT);
  if (t == nullptr) throw DdsError("cannot create topic " + dds_name + " of type " + type_name);
  topics_.emplace(topic_name, t);
  return t;
}

fdds::DataWriter* Participant::createWriter(fdds::Topic* topic, const std::string& profile) {
  fdds::DataWriterQos qos;
  if (publisher_->get_datawriter_qos_from_profile(profile, qos) != ReturnCode_t::RETCODE_OK) {
    throw DdsError("data_writer profile '" + profile + "' missing in the DDS XML profiles");
  }
  fdds::DataWriter* w = publisher_->create_datawriter(topic, qos);
  if (w == nullptr) throw DdsError("cannot create writer on " + topic->get_name() + " with profile " + profile);
  return w;
}

fdds::DataReader* Participant::createReader(fdds::Topic* topic, const std::string& profile,
                                            std::unique_ptr<fdds::DataReaderListener> listener) {
  fdds::DataReaderQos qos;
  if (subscriber_->get_datareader_qos_from_profile(profile, qos) != ReturnCode_t::RETCODE_OK) {
    throw DdsError("data_reader profile '" + profile + "' missing in the DDS XML profiles");
  }
  fdds::DataReader* r = subscriber_->create_datareader(topic, qos, listener.get());
  if (r == nullptr) throw DdsError("cannot create reader on " + topic->get_name() + " with profile " + profile);
  listeners_.push_back(std::move(listener));
  return r;
}

std::optional<Peer> Participant::twin() const {
  return peer_listener_->withBook([](PeerBook& book) { return book.oldestTwin(); });
}

bool Participant::mustGiveWay() const {
  return peer_listener_->withBook([](PeerBook& book) { return book.mustGiveWay(); });
}

Participant::PeersBack Participant::peersBackAfterLease() const {
  return peer_listener_->withBook([](PeerBook& book) {
    return PeersBack{book.returnedAfterLease(), book.lastReturned(), book.lastReturnedKey()};
  });
}

std::vector<PeerKey> Participant::takePeersGone() {
  return peer_listener_->withBook([](PeerBook& book) { return book.takeGone(); });
}

bool Participant::writerReadBy(const fdds::DataWriter* w, const PeerKey& peer) const {
  return peer_listener_->readBy(w, peer);
}

std::chrono::steady_clock::time_point Participant::lastAuthentication() const {
  return peer_listener_->lastAuthentication();
}

std::vector<int> Participant::ownSharedMemoryPorts() {
  const std::set<unsigned long> locked = lockedInodes(readWhole("/proc/locks"), static_cast<long>(::getpid()));
  std::vector<int> own;
  std::error_code ec;
  for (std::filesystem::directory_iterator it("/proc/self/fd", ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code link_ec;
    const std::optional<int> port = lockFilePort(std::filesystem::read_symlink(it->path(), link_ec).string());
    struct stat st {};
    if (link_ec || !port || ::stat(it->path().c_str(), &st) != 0) continue;
    if (locked.count(static_cast<unsigned long>(st.st_ino)) > 0) own.push_back(*port);
  }
  std::sort(own.begin(), own.end());
  own.erase(std::unique(own.begin(), own.end()), own.end());
  return own;
}

std::vector<int> Participant::deafSharedMemoryPorts() {
  const std::vector<int> own = ownSharedMemoryPorts();
  if (own.empty()) return {};
  return deafPorts(readWhole("/proc/self/maps"), own, [](int port) {
    std::error_code ec;
    return std::filesystem::exists("/dev/shm/fastrtps_port" + std::to_string(port), ec);
  });
}

}  // namespace swa::dds
