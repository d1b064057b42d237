// Participant's creation: from the XML profiles and the deployment (participant_qos.h), its publisher and subscriber,
// and the topics, writers and readers it makes. Its shutdown, discovery and endpoints are in files of their own.

#include "swa/dds/participant.h"

#include <cstdlib>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "participant_qos.h"
#include "peer_listener.h"
#include "swa/dds/deployment.h"
#include "swa/dds/security_check.h"

namespace swa::dds {

namespace fdds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;

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
  const PeerKey self_key = detail::keyOf(participant_->guid().guidPrefix);
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

}  // namespace swa::dds
