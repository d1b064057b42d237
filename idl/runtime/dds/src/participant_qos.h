#pragma once
// Internal to swa_dds: the QoS a participant is created with. The XML profile of the deployment's transport, then
// what the environment adds (deployment.h): shared-memory ports no earlier participant of this process used, the
// discovery servers, the DDS Security plugins with this participant's files, and this process's card in user data.

#include <optional>
#include <string>

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include "swa/dds/deployment.h"
#include "swa/dds/peer_book.h"
#include "swa/dds/security_check.h"

namespace swa::dds::detail {

// Profiles must be loaded before the first default QoS is read, and only once per process: a second file is an error.
void loadProfilesOnce(const std::string& file);

struct ParticipantSetup {
  eprosima::fastdds::dds::DomainParticipantQos qos;
  std::optional<SecurityFiles> security;  // when SWA_SECURITY_DIR is set
  PeerCard card;                          // what the peers learn of this process (peer_book.h)
};

// Throws DdsError naming what is missing: the profile, a credentials file, a malformed SWA_DISCOVERY_SERVER.
ParticipantSetup participantSetup(const std::string& name, int domain_id, const std::string& profiles_file,
                                  const Deployment& deployment);

// Why DDS Security refused `files` (Fast DDS itself only says "initialization error").
std::string refusalReason(const SecurityFiles& files);

}  // namespace swa::dds::detail
