#pragma once
// Internal to swa_dds: the participant's listener, which keeps what discovery reports (the PeerBook, which peers read
// each writer, the last authentication). Apart from participant.cpp: it is fed on Fast DDS's threads, under its own
// lock, and the lifecycle only creates it and hands it the participant's own key.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <utility>

#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/rtps/common/GuidPrefix_t.hpp>

#include "swa/dds/participant.h"
#include "swa/dds/peer_book.h"

namespace swa::dds {

namespace detail {

inline PeerKey keyOf(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix) {
  PeerKey key{};
  std::copy(prefix.value, prefix.value + key.size(), key.begin());
  return key;
}

}  // namespace detail

// Feeds the participant's PeerBook from discovery (peer_book.h). With SWA_DDS_TRACE=1 also one line on stderr per
// remote participant discovered / lost / authenticated, to see on a real network (or with DDS Security) who found
// whom. Only participant events: the data callbacks stay with the readers.
class Participant::PeerListener : public eprosima::fastdds::dds::DomainParticipantListener {
 public:
  PeerListener(std::string self, PeerCard card, bool trace)
      : self_(self), book_(std::move(self), std::move(card)), trace_(trace) {}

  void on_participant_discovery(eprosima::fastdds::dds::DomainParticipant*,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override;

#if HAVE_SECURITY
  void onParticipantAuthentication(eprosima::fastdds::dds::DomainParticipant*,
                                   eprosima::fastrtps::rtps::ParticipantAuthenticationInfo&& info) override;
#endif

  // Which participants read each of our writers: a matched reader's handle is its GUID, whose first 12 bytes are
  // its participant's prefix.
  void on_publication_matched(eprosima::fastdds::dds::DataWriter* writer,
                              const eprosima::fastdds::dds::PublicationMatchedStatus& status) override;

  bool readBy(const eprosima::fastdds::dds::DataWriter* writer, const PeerKey& peer);

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
  std::map<const eprosima::fastdds::dds::DataWriter*, std::multiset<PeerKey>> readers_;
};

}  // namespace swa::dds
