// Discovery as the participant keeps it: the listener's callbacks (peer_listener.h) and Participant's questions about
// its peers. Apart from participant.cpp: these run on Fast DDS's threads or read what those threads recorded.

#include "peer_listener.h"

#include <cstdio>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include <fastdds/rtps/participant/ParticipantDiscoveryInfo.h>

namespace swa::dds {

namespace fdds = eprosima::fastdds::dds;

void Participant::PeerListener::on_participant_discovery(fdds::DomainParticipant*,
                                                         eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) {
  using Status = eprosima::fastrtps::rtps::ParticipantDiscoveryInfo::DISCOVERY_STATUS;
  const PeerKey key = detail::keyOf(info.info.m_guid.guidPrefix);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (info.status == Status::DISCOVERED_PARTICIPANT || info.status == Status::CHANGED_QOS_PARTICIPANT) {
      const auto& bytes = info.info.m_userData.data_vec();
      book_.discovered(
          Peer{key, info.info.m_participantName.to_string(), decodePeerCard(std::string(bytes.begin(), bytes.end()))});
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
void Participant::PeerListener::onParticipantAuthentication(
    fdds::DomainParticipant*, eprosima::fastrtps::rtps::ParticipantAuthenticationInfo&& info) {
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

void Participant::PeerListener::on_publication_matched(fdds::DataWriter* writer,
                                                       const fdds::PublicationMatchedStatus& status) {
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

bool Participant::PeerListener::readBy(const fdds::DataWriter* writer, const PeerKey& peer) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto it = readers_.find(writer);
  return it != readers_.end() && it->second.count(peer) > 0;
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

std::vector<Peer> Participant::takeYoungerTwins() {
  return peer_listener_->withBook([](PeerBook& book) { return book.takeYoungerTwins(); });
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

}  // namespace swa::dds
