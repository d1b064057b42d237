#include "participant_qos.h"

#include <chrono>
#include <filesystem>
#include <mutex>
#include <set>
#include <vector>

#include <unistd.h>

#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

#include "swa/app/udp_port.h"
#include "swa/dds/participant.h"
#include "swa/dds/participant_id.h"

namespace swa::dds::detail {

namespace fdds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;

namespace {

std::string fileUri(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path abs = std::filesystem::absolute(path, ec);
  return "file://" + (ec ? path : abs.lexically_normal().string());
}

// DDS Security 1.1 builtin plugins (authentication, access control, encryption) with this participant's files.
void addSecurity(fdds::DomainParticipantQos& qos, const SecurityFiles& f) {
  auto& props = qos.properties().properties();
  const auto set = [&props](const std::string& name, const std::string& value) { props.emplace_back(name, value); };
  set("dds.sec.auth.plugin", "builtin.PKI-DH");
  set("dds.sec.auth.builtin.PKI-DH.identity_ca", fileUri(f.ca));
  set("dds.sec.auth.builtin.PKI-DH.identity_certificate", fileUri(f.certificate));
  set("dds.sec.auth.builtin.PKI-DH.private_key", fileUri(f.private_key));
  set("dds.sec.access.plugin", "builtin.Access-Permissions");
  set("dds.sec.access.builtin.Access-Permissions.permissions_ca", fileUri(f.ca));
  set("dds.sec.access.builtin.Access-Permissions.governance", fileUri(f.governance));
  set("dds.sec.access.builtin.Access-Permissions.permissions", fileUri(f.permissions));
  set("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

PeerCard selfCard(const std::string& swarm) {
  PeerCard card;
  card.swarm = swarm;
  // The process's start, not the participant's: a participant re-created later must not look younger than a twin.
  static const std::int64_t process_started_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  card.started_ns = process_started_ns;
  card.pid = static_cast<long>(::getpid());
  char host[256] = {};
  if (::gethostname(host, sizeof host - 1) == 0) card.host = host;
  return card;
}

// SWA_TRANSPORT=discovery-server: a CLIENT of the servers listed (position in the list = server id, as
// fast-discovery-server -i expects).
void useDiscoveryServers(fdds::DomainParticipantQos& qos, const std::string& servers) {
  auto& discovery = qos.wire_protocol().builtin.discovery_config;
  discovery.discoveryProtocol = eprosima::fastrtps::rtps::DiscoveryProtocol_t::CLIENT;
  if (!eprosima::fastdds::rtps::load_environment_server_info(servers, discovery.m_DiscoveryServers)) {
    throw DdsError("SWA_DISCOVERY_SERVER '" + servers + "' is not IP:PORT[;IP:PORT...]");
  }
}

// SWA_SECURITY_DIR: every file must be readable before Fast DDS sees them, so a missing one is named as such.
void useSecurity(fdds::DomainParticipantQos& qos, const SecurityFiles& files, const std::string& dir,
                 const std::string& name) {
  const auto unreadable = unreadableFiles(files);
  if (!unreadable.empty()) {
    std::string list;
    for (const auto& f : unreadable) list += "\n  " + f;
    throw DdsError("DDS Security (SWA_SECURITY_DIR=" + dir + "): no credentials for participant '" + name +
                   "', cannot read:" + list +
                   "\n(create them with deploy/security/make-credentials.sh, or unset SWA_SECURITY_DIR)");
  }
  addSecurity(qos, files);
}

// The participant id (participant_id.h), for every transport: past 101 participants on a host Fast DDS 2.9 finds no
// port by itself. With shared memory (the local transport) also no id whose port a killed process left behind: a peer
// that sent to that one keeps the deleted port mapped, and a participant re-created after a peer's lease expired
// (agent_node.cpp) would never hear from that peer again (measured: 1 realtime run in 10 with a CPU hog, the
// re-created agent's UAV on failsafe). Nor does a participant take the ports of one this process deleted before, for
// the same reason. A profile that sets an id keeps it.
void chooseParticipantId(fdds::DomainParticipantQos& qos, int domain_id, bool shared_memory) {
  fdds::WireProtocolConfigQos& wire = qos.wire_protocol();
  if (wire.participant_id >= 0) return;
  const auto& p = wire.port;
  const PortMapping ports{static_cast<int>(p.portBase),          static_cast<int>(p.domainIDGain),
                          static_cast<int>(p.participantIDGain), static_cast<int>(p.offsetd0),
                          static_cast<int>(p.offsetd2),          static_cast<int>(p.offsetd1),
                          static_cast<int>(p.offsetd3)};
  static std::mutex used_mutex;
  static std::set<int> used;  // unicast ports of the participants this process created
  const std::lock_guard<std::mutex> lock(used_mutex);
  const auto exists = [shared_memory](int port) {
    std::error_code ec;
    return used.count(port) > 0 || app::udpPortInUse(port) ||
           (shared_memory && std::filesystem::exists("/dev/shm/fastrtps_port" + std::to_string(port), ec));
  };
  // None left (every port of two domains' ranges taken or abandoned: `fastdds shm clean`): Fast DDS's own choice.
  if (const std::optional<int> id = unusedParticipantId(domain_id, ports, exists)) {
    wire.participant_id = *id;
    const auto [meta, user] = unicastPorts(domain_id, ports, *id);
    used.insert(meta);
    used.insert(user);
  }
}

}  // namespace

void loadProfilesOnce(const std::string& file) {
  static std::mutex mutex;
  static std::string loaded;
  std::lock_guard<std::mutex> lock(mutex);
  if (!loaded.empty()) {
    if (loaded != file) throw DdsError("XML profiles already loaded from " + loaded + ", cannot switch to " + file);
    return;
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw DdsError("DDS XML profiles file not found: " + file + " (set SWA_DDS_PROFILES to override)");
  }
  if (fdds::DomainParticipantFactory::get_instance()->load_XML_profiles_file(file) != ReturnCode_t::RETCODE_OK) {
    throw DdsError("cannot load DDS XML profiles from " + file + " (see the Fast DDS XML parser error above)");
  }
  loaded = file;
}

ParticipantSetup participantSetup(const std::string& name, int domain_id, const std::string& profiles_file,
                                  const Deployment& deployment) {
  ParticipantSetup setup;
  fdds::DomainParticipantQos& qos = setup.qos;
  const char* profile = participantProfile(deployment.transport);
  if (fdds::DomainParticipantFactory::get_instance()->get_participant_qos_from_profile(profile, qos) !=
      ReturnCode_t::RETCODE_OK) {
    throw DdsError(std::string("participant profile '") + profile + "' missing in " + profiles_file);
  }
  qos.name(name);
  chooseParticipantId(qos, domain_id, deployment.transport == Transport::kLocal);
  if (deployment.transport == Transport::kDiscoveryServer) useDiscoveryServers(qos, deployment.discovery_servers);
  if (!deployment.security_dir.empty()) {
    setup.security = securityFiles(deployment.security_dir, name);
    useSecurity(qos, *setup.security, deployment.security_dir, name);
  }
  setup.card = selfCard(swarmIdentity(deployment));
  const std::string card_text = encodePeerCard(setup.card);
  qos.user_data().data_vec(std::vector<eprosima::fastrtps::rtps::octet>(card_text.begin(), card_text.end()));
  return setup;
}

// Fast DDS says only "initialization error" when it refuses credentials: its plugins' checks are repeated on the
// files to name the one that failed.
std::string refusalReason(const SecurityFiles& files) {
  if (const auto problem = credentialProblem(files)) return *problem;
  // Fast DDS 2.9.1 creates the participant when the documents do not cover its domain (endpoints fail later):
  // what is left are the grant's dates and the XML itself.
  return "no problem found in them (" + files.certificate + " verifies against " + files.ca + " and matches " +
         files.private_key + ", the signatures of " + files.governance + " and " + files.permissions +
         " verify, the grant names the certificate's subject); left: the grant is outside its validity dates (read "
         "as local time), a document is not XML Fast DDS accepts, or the failure is not about security (see the "
         "Fast DDS errors above)";
}

}  // namespace swa::dds::detail
