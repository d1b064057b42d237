#pragma once
// Command line of swa_launch. Parsing is separate from main() so it can be tested; every problem is reported at once.

#include <optional>
#include <string>
#include <vector>

#include "swa/agent/config.h"
#include "swa/recording/record_set.h"

namespace swa::launch {

// The discovery server swa_launch starts listens on the first free UDP port from here (Fast DDS's default).
constexpr int kDefaultDiscoveryPort = 11811;

// Past this many UAV processes (agents and bridges) on one host swa_launch uses a discovery server of its own unless
// a transport is given. With multicast discovery every participant announces every endpoint to every other one;
// through a server a process learns only of those it shares a topic with. bench_scale on 2 cores, lockstep, both
// transports alternated twice: at 32 alike (1.9-2.4 s to discover, 3.2-3.4 ms per step); at 64 multicast took
// 9.6-11.4 s to discover and 11.7-16.2 ms per step, the server 2.0-2.2 s and 8.5-8.7 ms; 100 never matched by
// multicast within 60 s (load average 88), 4.5 s through the server.
constexpr int kMaxUavProcessesForSimpleDiscovery = 32;

// With DDS Security, every participant authenticates every other one, at a CPU cost on both sides; started all at
// once, 18 secured processes (8 UAVs through an autopilot) on 2 cores left handshakes stalled and fed reconnection
// storms (deploy/README.md, "A known Fast DDS 2.9 problem with security"; BENCHMARKS.md, "Secure launches").
constexpr double kSecureStaggerS = 0.5;

struct LaunchOptions {
  std::string scenario_path;           // --scenario FILE (required)
  std::vector<std::string> overrides;  // --set key=value, in order; passed to sim, agents' config and monitor
  std::string out_dir = "out/launch";  // --out DIR
  std::optional<agent::Mode> compare;  // --compare MODE: a second run in that mode, same seed, one report
  std::optional<std::string> domain;   // --domain D (else SWA_DOMAIN, else 0)
  std::string bin_dir;                 // --bin-dir DIR (default: the directory of swa_launch itself)
  int max_restarts = 5;                // per agent and run; then the agent stays down
  double restart_backoff_s = 0.5;      // first restart delay; doubles per restart of the same agent
  double restart_backoff_max_s = 8.0;
  double agent_timeout_s = 2.0;  // passed to swa_sim --agent-timeout-s
  double timeout_s = 0.0;        // wall bound of each run; 0 = none
  double grace_s = 10.0;         // SIGTERM -> SIGKILL grace when stopping children
  // --stagger-s T: the simulator and the monitor first, then one UAV process every T seconds (0: all at once, the
  // simulator last). Unset: kSecureStaggerS with --secure, else 0.
  std::optional<double> stagger_s;
  std::string transport;              // --transport local|network|discovery-server (else $SWA_TRANSPORT)
  std::string discovery_server;       // --discovery-server IP:PORT[;...]: use these instead of starting one
  std::optional<int> discovery_port;  // --discovery-port: of the server swa_launch starts on 127.0.0.1
  std::string secure_dir;             // --secure DIR: DDS Security with the credentials in DIR
  std::string swarm;                  // --swarm NAME | none (else $SWA_SWARM, else a new name per launch)
  std::string vehicle;                // --vehicle direct|px4|ardupilot: sets vehicle.interface (one bridge per agent)
  std::string naming;                 // --naming swa|ros2 (else $SWA_NAMING, else swa)
  std::string ros_namespace;          // --ros-namespace NS (ros2 naming; else $SWA_ROS_NAMESPACE)
  bool record = false;                // --record[=SET]: each run's monitor records it into <run dir>/run.mcap
  recording::RecordSet record_set = recording::RecordSet::kAll;  // --record=monitor: only the monitor's own topics
  std::string live;  // --live [ADDR:]PORT: passed to the monitor (empty: no live view)
  bool help = false;
};

// The stagger a launch uses (LaunchOptions::stagger_s).
double staggerOf(const LaunchOptions& o);

// Accepts "--opt value" and "--opt=value" (--record takes a value only as --record=SET). Throws
// std::invalid_argument listing every problem, one per line.
LaunchOptions parseLaunchOptions(const std::vector<std::string>& args);

// The transport swa_launch chooses itself: "discovery-server" for more than kMaxUavProcessesForSimpleDiscovery UAV
// processes when no transport was asked for (neither --transport nor `env_transport`, the value of $SWA_TRANSPORT,
// null if unset), no servers were named and DDS Security is off (a server would need credentials of its own);
// otherwise nothing, and the asked-for transport or local applies.
std::optional<std::string> automaticTransport(const LaunchOptions& o, const char* env_transport, int uav_processes);
std::string launchUsage();

}  // namespace swa::launch
