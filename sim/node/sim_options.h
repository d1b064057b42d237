#pragma once
// Command line of swa_sim. Parsing is separate from main() so it can be tested; every problem is reported at once.

#include <optional>
#include <string>
#include <vector>

namespace swa::sim_node {

// Wall seconds to wait for every agent at the start. With DDS Security (SWA_SECURITY_DIR set) the start must leave room
// for a stalled handshake's re-creation and, when Fast DDS 2.9 deadlocks inside a participant, for its bounded 12 s
// deletion and the process's restart: 8-UAV secure launches through ArduPilot took up to 49 s to full discovery on
// 2 cores, and in the one of 38 launches whose stuck agent was restarted, the 60 s timeout ended the run 4 s after the
// restart (BENCHMARKS.md, secure launches).
constexpr double kStartupTimeoutS = 60.0;
constexpr double kSecureStartupTimeoutS = 120.0;

struct SimOptions {
  std::string scenario_path;           // --scenario FILE (required)
  std::vector<std::string> overrides;  // --set key=value, in order
  std::optional<std::string> domain;   // --domain D (else SWA_DOMAIN, else 0)
  double agent_timeout_s = 2.0;        // lockstep: wall time to wait for an answer before an agent is dead
  // Wall time to wait for every agent's endpoints to be discovered (kSecureStartupTimeoutS with DDS Security).
  double startup_timeout_s = kStartupTimeoutS;
  int truth_every = 10;             // publish swa/truth every N steps (and at the last step)
  std::string truth_out;            // --truth-out FILE: every published truth sample as CSV
  std::string summary_out;          // --summary-out FILE: JSON summary of the run
  std::string export_agent_config;  // --export-agent-config FILE: write the agents' config and exit
  int wait_monitors = 0;            // --wait-monitors N: also wait for N readers of swa/truth and swa/events
  bool help = false;
  bool list_parameters = false;
};

// Accepts "--opt value" and "--opt=value". Throws std::invalid_argument listing every problem, one per line.
SimOptions parseSimOptions(const std::vector<std::string>& args);
std::string simUsage();

}  // namespace swa::sim_node
