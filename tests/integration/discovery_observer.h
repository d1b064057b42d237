#pragma once
// A participant that only listens to discovery and keeps every reader and writer it hears of (with the name and GUID
// of its participant, topic and type), for the audits of what SWA's processes put on a domain: the isolation audit
// (test_isolation.cpp, isolation_audit.h) and the ROS 2 names (tests/ros2/). Created from the same XML profile as
// every SWA process (same discovery settings and transports). Discovery reports endpoints of every partition.

#include <unistd.h>

#include <chrono>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fastdds/rtps/participant/ParticipantDiscoveryInfo.h>
#include <fastdds/rtps/reader/ReaderDiscoveryInfo.h>
#include <fastdds/rtps/writer/WriterDiscoveryInfo.h>
#include <fastdds/dds/core/status/StatusMask.hpp>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include "isolation_audit.h"
#include "swa/dds/options.h"
#include "swa/dds/participant.h"
#include "swa/dds/qos_profiles.h"
#include "test_domain.h"

namespace swa::testing {

namespace discovery_detail {
namespace fdds = eprosima::fastdds::dds;
namespace rtps = eprosima::fastrtps::rtps;
using eprosima::fastrtps::types::ReturnCode_t;

inline std::string text(const rtps::GuidPrefix_t& prefix) {
  std::ostringstream s;
  s << prefix;
  return s.str();
}

// Everything discovery reports, keyed by GUID; called on Fast DDS threads. Removals are ignored on purpose: an
// endpoint that existed at any time during the run is audited.
class DiscoveryLog : public fdds::DomainParticipantListener {
 public:
  void on_participant_discovery(fdds::DomainParticipant* /*self*/, rtps::ParticipantDiscoveryInfo&& info) override {
    if (info.status != rtps::ParticipantDiscoveryInfo::DISCOVERED_PARTICIPANT &&
        info.status != rtps::ParticipantDiscoveryInfo::CHANGED_QOS_PARTICIPANT) {
      return;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    names_[text(info.info.m_guid.guidPrefix)] = info.info.m_participantName.to_string();
  }

  void on_subscriber_discovery(fdds::DomainParticipant* /*self*/, rtps::ReaderDiscoveryInfo&& info) override {
    if (info.status == rtps::ReaderDiscoveryInfo::REMOVED_READER) return;
    record(EndpointKind::kReader, info.info.guid(), info.info.topicName().to_string(),
           info.info.typeName().to_string());
  }

  void on_publisher_discovery(fdds::DomainParticipant* /*self*/, rtps::WriterDiscoveryInfo&& info) override {
    if (info.status == rtps::WriterDiscoveryInfo::REMOVED_WRITER) return;
    record(EndpointKind::kWriter, info.info.guid(), info.info.topicName().to_string(),
           info.info.typeName().to_string());
  }

  std::size_t participantCount() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return names_.size();
  }

  // Every endpoint seen so far, with the name its participant announced (empty if never announced).
  std::vector<Endpoint> endpoints() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<Endpoint> out;
    for (const auto& [guid, e] : endpoints_) {
      Endpoint x = e;
      const auto name = names_.find(x.participant_guid);
      if (name != names_.end()) x.participant = name->second;
      out.push_back(std::move(x));
    }
    return out;
  }

 private:
  void record(EndpointKind kind, const rtps::GUID_t& guid, std::string topic, std::string type) {
    std::ostringstream key;
    key << guid;
    std::lock_guard<std::mutex> lock(mutex_);
    endpoints_[key.str()] = Endpoint{kind, "", text(guid.guidPrefix), std::move(topic), std::move(type)};
  }

  mutable std::mutex mutex_;
  std::map<std::string, std::string> names_;   // participant GUID prefix -> announced name
  std::map<std::string, Endpoint> endpoints_;  // endpoint GUID -> endpoint (participant name resolved later)
};

// A participant with no endpoints of its own that only listens to discovery, created from the same XML profile as
// every SWA process (same discovery settings and transports).
class DiscoveryObserver {
 public:
  explicit DiscoveryObserver(int domain, const std::string& name = "swa_test_discovery_observer") {
    auto* factory = fdds::DomainParticipantFactory::get_instance();
    const std::string profiles = dds::resolveProfilesFile();
    // Profiles before any default QoS is read (FASTDDS-NOTES); loading the same file again is harmless.
    if (factory->load_XML_profiles_file(profiles) != ReturnCode_t::RETCODE_OK) {
      throw dds::DdsError("cannot load DDS XML profiles from " + profiles);
    }
    fdds::DomainParticipantQos qos;
    if (factory->get_participant_qos_from_profile(dds::qos::kParticipant, qos) != ReturnCode_t::RETCODE_OK) {
      throw dds::DdsError(std::string("participant profile '") + dds::qos::kParticipant + "' missing in " + profiles);
    }
    qos.name(name);
    // The discovery callbacks do not depend on the mask; data callbacks are masked out as FASTDDS-NOTES advises
    // (this participant has no reader anyway).
    fdds::StatusMask mask = fdds::StatusMask::all();
    mask >> fdds::StatusMask::data_on_readers() >> fdds::StatusMask::data_available();
    participant_ = factory->create_participant(static_cast<fdds::DomainId_t>(domain), qos, &log_, mask);
    if (participant_ == nullptr)
      throw dds::DdsError("cannot create the observer participant on domain " + std::to_string(domain));
  }
  ~DiscoveryObserver() { fdds::DomainParticipantFactory::get_instance()->delete_participant(participant_); }
  DiscoveryObserver(const DiscoveryObserver&) = delete;
  DiscoveryObserver& operator=(const DiscoveryObserver&) = delete;

  const DiscoveryLog& log() const { return log_; }

 private:
  DiscoveryLog log_;  // declared first: outlives the participant that calls it
  fdds::DomainParticipant* participant_ = nullptr;
};

}  // namespace discovery_detail

using discovery_detail::DiscoveryLog;
using discovery_detail::DiscoveryObserver;

// An observer on a private domain (reserved, test_domain.h: the first free one from 100..199 up) that is also quiet:
// anything already on it would pollute an audit, so the observer listens for a moment first (the profile announces
// every 1 s) and moves on if it hears anyone. Sets `domain`; null if no domain is free or five were all in use.
inline std::unique_ptr<DiscoveryObserver> observeQuietDomain(int& domain, const std::string& name) {
  for (int attempt = 0; attempt < 5; ++attempt) {
    domain = reserveTestDomain(100 + (::getpid() + 37 * attempt) % 100);
    if (domain < 0) return nullptr;
    auto observer = std::make_unique<DiscoveryObserver>(domain, name);
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    if (observer->log().participantCount() == 0) return observer;
    std::cerr << "domain " << domain << " is in use, trying another one\n";
  }
  return nullptr;
}

}  // namespace swa::testing
