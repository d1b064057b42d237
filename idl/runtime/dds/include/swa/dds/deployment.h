#pragma once
// How a SWA process joins the DDS network, chosen by the environment so that one binary serves the laptop, the
// container and the drone (deploy/README.md): the transport profile, the discovery servers, the DDS Security
// credentials. No DDS include: the parsing is tested on its own; swa::dds::Participant applies the result.
//
//   SWA_TRANSPORT         local (default): shared memory + UDPv4, multicast discovery — processes on one host
//                         network: UDPv4 only, multicast discovery — containers, hosts on a LAN with multicast
//                         discovery-server: UDPv4 only, discovery through Fast DDS Discovery Server(s)
//   SWA_DISCOVERY_SERVER  IP:PORT[;IP:PORT...] of the servers (required by, and only allowed with, discovery-server);
//                         list position = server id, as `fastdds discovery -i <id>` expects
//   SWA_SECURITY_DIR      directory of DDS Security credentials (deploy/security/make-credentials.sh); unset = off
//   SWA_SWARM             the swarm (run) this process belongs to: its readers and writers are in the DDS partition
//                         "swa.<name>", so two swarms on one domain never exchange a sample. Unset = the default
//                         partition (what plain DDS and ROS 2 tools use). swa_launch sets one per run.
//   SWA_NAMING            swa (default) | ros2: the names of topics and types on the wire (naming.h)
//   SWA_ROS_NAMESPACE     with ros2: a ROS namespace in front of every SWA topic

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "swa/dds/naming.h"

namespace swa::dds {

enum class Transport { kLocal, kNetwork, kDiscoveryServer };

struct Deployment {
  Transport transport = Transport::kLocal;
  std::string discovery_servers;  // SWA_DISCOVERY_SERVER, verbatim
  std::string security_dir;       // empty: DDS Security off
  std::string swarm;              // SWA_SWARM; empty: the default partition
  WireNames names;                // SWA_NAMING, SWA_ROS_NAMESPACE
};

// The swarm a process belongs to as its peers compare it (twins, peer_book.h): SWA_SWARM and, in the ros2 naming, the
// ROS namespace (two swarms in two namespaces share no topic), as "<swarm>@/<namespace>".
std::string swarmIdentity(const Deployment& d);

// The DDS partition of a swarm: "swa.<name>".
std::string swarmPartition(const std::string& swarm);
// Why `name` is not a usable SWA_SWARM (1 to 64 of A-Z a-z 0-9 . _ -), if it is not.
std::optional<std::string> swarmNameProblem(const std::string& name);

// Environment lookup, injectable for tests; nullopt = variable not set.
using EnvLookup = std::function<std::optional<std::string>(const std::string&)>;

// Reads the variables. Throws std::invalid_argument naming the variable and the accepted values.
Deployment parseDeployment(const EnvLookup& env);
Deployment resolveDeployment();  // from the process environment

const char* transportName(Transport t);
std::optional<Transport> parseTransport(const std::string& name);

// The "Environment:" section shared by every node's --help: domain, profiles, transport, discovery, security.
std::string environmentHelp();

// The participant profile of idl/runtime/dds/profiles.xml used for a transport.
const char* participantProfile(Transport t);

// Checks one "IP:PORT" list entry by entry (dotted IPv4, port 1..65535); the problems found, empty if fine.
std::vector<std::string> checkServerList(const std::string& list);

// The credential files of one participant: <dir>/ca.pem (signs identities and documents), <dir>/governance.p7s,
// <dir>/<participant name>/{cert.pem,key.pem,permissions.p7s}.
struct SecurityFiles {
  std::string ca, governance, certificate, private_key, permissions;
};
SecurityFiles securityFiles(const std::string& dir, const std::string& participant_name);

// The files of `f` that do not exist or cannot be read.
std::vector<std::string> unreadableFiles(const SecurityFiles& f);

}  // namespace swa::dds
