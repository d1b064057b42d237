#include "swa/dds/deployment.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <utility>

#include "name_table.h"
#include "swa/app/number.h"
#include "swa/dds/qos_profiles.h"

namespace swa::dds {
namespace {

constexpr std::pair<Transport, const char*> kTransportNames[] = {
    {Transport::kLocal, "local"}, {Transport::kNetwork, "network"}, {Transport::kDiscoveryServer, "discovery-server"}};

bool isDottedIpv4(const std::string& s) {
  int parts = 0;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = s.find('.', start);
    const std::string part = s.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (part.empty() || part.size() > 3 || !app::parseInteger(part, 0, 255)) return false;
    ++parts;
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return parts == 4;
}

}  // namespace

const char* transportName(Transport t) { return detail::nameIn(kTransportNames, t); }

std::optional<Transport> parseTransport(const std::string& name) { return detail::valueIn(kTransportNames, name); }

const char* participantProfile(Transport t) {
  // discovery-server uses the network profile: the CLIENT role and the servers are set from SWA_DISCOVERY_SERVER
  // (addresses known only at deployment, not in a shipped XML file).
  return t == Transport::kLocal ? qos::kParticipant : qos::kParticipantNetwork;
}

std::vector<std::string> checkServerList(const std::string& list) {
  std::vector<std::string> problems;
  if (list.empty()) return {"the list is empty"};
  std::size_t start = 0;
  while (true) {
    const std::size_t semi = list.find(';', start);
    const std::string entry = list.substr(start, semi == std::string::npos ? std::string::npos : semi - start);
    const std::size_t colon = entry.rfind(':');
    if (colon == std::string::npos || !isDottedIpv4(entry.substr(0, colon)) ||
        !app::parseInteger(entry.substr(colon + 1), 1, 65535)) {
      problems.push_back("'" + entry + "' is not IPv4:PORT (e.g. 10.0.0.1:11811)");
    }
    if (semi == std::string::npos) break;
    start = semi + 1;
  }
  return problems;
}

Deployment parseDeployment(const EnvLookup& env) {
  Deployment d;
  if (const auto t = env("SWA_TRANSPORT"); t && !t->empty()) {
    const auto parsed = parseTransport(*t);
    if (!parsed) {
      throw std::invalid_argument("SWA_TRANSPORT '" + *t + "' is not one of local, network, discovery-server");
    }
    d.transport = *parsed;
  }
  if (const auto s = env("SWA_DISCOVERY_SERVER"); s && !s->empty()) d.discovery_servers = *s;
  if (d.transport == Transport::kDiscoveryServer) {
    if (d.discovery_servers.empty()) {
      throw std::invalid_argument(
          "SWA_TRANSPORT=discovery-server needs SWA_DISCOVERY_SERVER=IP:PORT[;IP:PORT...] (the servers' addresses)");
    }
    const auto problems = checkServerList(d.discovery_servers);
    if (!problems.empty()) throw std::invalid_argument("SWA_DISCOVERY_SERVER: " + problems.front());
  } else if (!d.discovery_servers.empty()) {
    // Silently ignoring it would leave a user wondering why the server never sees the swarm.
    throw std::invalid_argument(std::string("SWA_DISCOVERY_SERVER is set but SWA_TRANSPORT is ") +
                                transportName(d.transport) + ": set SWA_TRANSPORT=discovery-server or unset it");
  }
  if (const auto s = env("SWA_SECURITY_DIR"); s && !s->empty()) d.security_dir = *s;
  if (const auto s = env("SWA_SWARM"); s && !s->empty()) {
    if (const auto problem = swarmNameProblem(*s)) throw std::invalid_argument("SWA_SWARM: " + *problem);
    d.swarm = *s;
  }
  if (!d.swarm.empty() && !d.security_dir.empty()) {
    // The permissions of make-credentials.sh grant the default partition only: every endpoint would be refused.
    throw std::invalid_argument(
        "SWA_SWARM cannot be combined with SWA_SECURITY_DIR: the permissions grant the default partition only; with "
        "DDS Security, credentials (or a domain) keep swarms apart");
  }
  if (const auto n = env("SWA_NAMING"); n && !n->empty()) {
    const auto parsed = parseNaming(*n);
    if (!parsed) throw std::invalid_argument("SWA_NAMING '" + *n + "' is not one of swa, ros2");
    d.names.naming = *parsed;
  }
  if (const auto ns = env("SWA_ROS_NAMESPACE"); ns && !ns->empty()) {
    if (d.names.naming != Naming::kRos2) {
      throw std::invalid_argument(
          "SWA_ROS_NAMESPACE is set but SWA_NAMING is not ros2: set SWA_NAMING=ros2 or unset it");
    }
    if (const auto problem = rosNamespaceProblem(*ns)) throw std::invalid_argument("SWA_ROS_NAMESPACE: " + *problem);
    d.names.ros_namespace = normalRosNamespace(*ns);
  }
  return d;
}

std::string swarmIdentity(const Deployment& d) {
  if (d.names.naming != Naming::kRos2 || d.names.ros_namespace.empty()) return d.swarm;
  return d.swarm + "@/" + d.names.ros_namespace;
}

std::string swarmPartition(const std::string& swarm) { return "swa." + swarm; }

std::optional<std::string> swarmNameProblem(const std::string& name) {
  const bool ok_chars = std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' ||
           c == '-';
  });
  if (name.empty() || name.size() > 64 || !ok_chars) {
    return "'" + name.substr(0, 80) + "' must be 1 to 64 letters, digits, '.', '_' or '-'";
  }
  return std::nullopt;
}

Deployment resolveDeployment() {
  return parseDeployment([](const std::string& name) -> std::optional<std::string> {
    const char* v = std::getenv(name.c_str());
    if (v == nullptr) return std::nullopt;
    return std::string(v);
  });
}

std::string environmentHelp() {
  return R"(Environment (deploy/README.md):
  SWA_DOMAIN            DDS domain id when --domain is not given (default 0)
  SWA_DDS_PROFILES      Fast DDS XML profiles (default: share/swa/profiles.xml beside an installed program's
                        bin/, else idl/runtime/dds/profiles.xml of the source tree)
  SWA_TRANSPORT         local (default: shared memory + UDP, one host) | network (UDPv4 only, multicast
                        discovery: containers, hosts) | discovery-server (UDPv4, no multicast needed)
  SWA_DISCOVERY_SERVER  IP:PORT[;IP:PORT...] of the Fast DDS Discovery Server(s), with discovery-server
  SWA_SECURITY_DIR      DDS Security credentials (deploy/security/make-credentials.sh); unset = security off
  SWA_SWARM             the swarm (run) of this process: DDS partition swa.<name>, so swarms sharing a domain
                        never mix; every process of a run needs the same (swa_launch sets one per run; not with
                        SWA_SECURITY_DIR); unset = the default partition
  SWA_NAMING            swa (default: topics swa/uav1/imu, types swa::msg::Imu) | ros2 (ROS 2's mapping: topics
                        rt/swa/uav1/imu, types swa_msgs::msg::dds_::Imu_, seen by ros2 topic list/echo/bag);
                        every process of a swarm needs the same
  SWA_ROS_NAMESPACE     with ros2: a ROS namespace in front of every SWA topic (rt/<ns>/swa/...), so two swarms
                        can share a domain
)";
}

SecurityFiles securityFiles(const std::string& dir, const std::string& participant_name) {
  const std::string own = dir + "/" + participant_name + "/";
  return SecurityFiles{dir + "/ca.pem", dir + "/governance.p7s", own + "cert.pem", own + "key.pem",
                       own + "permissions.p7s"};
}

std::vector<std::string> unreadableFiles(const SecurityFiles& f) {
  std::vector<std::string> out;
  for (const std::string* p : {&f.ca, &f.governance, &f.certificate, &f.private_key, &f.permissions}) {
    if (!std::ifstream(*p).good()) out.push_back(*p);
  }
  return out;
}

}  // namespace swa::dds
