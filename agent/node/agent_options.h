#pragma once
// Command line of swa_agent. Parsing is separate from main() so it can be tested; every problem is reported at once.

#include <optional>
#include <string>
#include <vector>

namespace swa::agent_node {

// UAV ids are small non-negative integers (the simulator numbers them 0..N-1); the bound keeps topic names sane.
constexpr int kMaxUavId = 9999;

struct AgentOptions {
  int id = -1;                         // --id I (required)
  std::string config_path;             // --config FILE (empty: defaults)
  std::vector<std::string> overrides;  // --set key=value, in order
  std::optional<std::string> domain;   // --domain D (else SWA_DOMAIN, else 0)
  bool help = false;
  bool list_parameters = false;
};

// Accepts "--opt value" and "--opt=value". Throws std::invalid_argument listing every problem, one per line.
AgentOptions parseAgentOptions(const std::vector<std::string>& args);
std::string agentUsage();

}  // namespace swa::agent_node
