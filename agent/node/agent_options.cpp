#include "agent_options.h"

#include <sstream>
#include <stdexcept>

#include "swa/dds/deployment.h"
#include "swa/dds/options.h"

namespace swa::agent_node {

AgentOptions parseAgentOptions(const std::vector<std::string>& args) {
  AgentOptions o;
  std::vector<std::string> problems;
  bool have_id = false;
  dds::ArgWalker walker(args, problems);
  while (walker.next()) {
    const std::string& key = walker.key();
    const auto value = [&walker] { return walker.value(); };
    if (key == "--help" || key == "-h") {
      o.help = true;
    } else if (key == "--parameters") {
      o.list_parameters = true;
    } else if (key == "--id") {
      if (const auto v = value()) {
        const auto id = dds::parseInteger(*v, 0, kMaxUavId);
        if (!id) {
          problems.push_back("--id '" + *v + "' is not a UAV id (an integer in [0, " + std::to_string(kMaxUavId) +
                             "])");
        } else {
          o.id = static_cast<int>(*id);
          have_id = true;
        }
      }
    } else if (key == "--config") {
      if (const auto v = value()) {
        if (v->empty()) problems.push_back("--config needs a file name");
        o.config_path = *v;
      }
    } else if (key == "--scenario") {
      if (const auto v = value()) {
        if (v->empty()) problems.push_back("--scenario needs a file name");
        o.scenario_path = *v;
      }
    } else if (key == "--set") {
      if (const auto v = value()) o.overrides.push_back(*v);
    } else if (key == "--domain") {
      if (const auto v = value()) o.domain = *v;
    } else {
      problems.push_back("unknown argument '" + walker.raw() + "' (see --help)");
    }
  }
  if (!have_id && !o.help && !o.list_parameters && problems.empty()) problems.push_back("--id is required");
  if (!o.config_path.empty() && !o.scenario_path.empty()) {
    problems.push_back("--config and --scenario both give the agent's parameters; use one");
  }
  if (!problems.empty()) {
    std::ostringstream msg;
    for (std::size_t k = 0; k < problems.size(); ++k) msg << (k ? "\n" : "") << problems[k];
    throw std::invalid_argument(msg.str());
  }
  return o;
}

std::string agentUsage() {
  return R"(swa_agent: the SWA agent of one UAV as a Fast DDS process.

Usage: swa_agent --id I [--config FILE | --scenario FILE] [--set key=value]... [--domain D]

Reads only   swa/uav<I>/imu, swa/uav<I>/detections, swa/uav<I>/gnss
Writes only  swa/uav<I>/cmd_vel (one VelocitySetpoint per IMU sample, echoing its stamp and seq)
             swa/uav<I>/state   (AgentState diagnostics, 10 Hz of sample time)

Options:
  --id I            UAV index, 0..9999 (required); participant name swa_agent_<I>
  --config FILE     agent parameters (YAML, layout of deploy/config/agent.yaml); default: built-in defaults.
                    `swa_sim --export-agent-config FILE` writes the one a scenario implies.
  --scenario FILE   the `agent:` section of a scenario file (swa_launch passes its run's scenario.yaml)
  --set key=value   override one parameter, e.g. --set formation.k=2 (repeatable, applied in order)
  --domain D        DDS domain id 0..232 (default: $SWA_DOMAIN, else 0)
  --parameters      list every agent parameter (key, unit, bounds, default) and exit
  -h, --help        this text

Runs until SIGINT or SIGTERM, then deletes its DDS entities and exits 0.
One agent per UAV and swarm: when another swa_agent with the same --id runs in the same swarm (SWA_SWARM) on the
domain, the one started later refuses to run (exit 3) and the other logs it.
Exit status: 0 stopped by a signal; 1 DDS failure (also: security credentials refused); 2 bad arguments or
             configuration (nothing started); 3 refused: an older agent with this --id runs in this swarm.

)" + dds::environmentHelp();
}

}  // namespace swa::agent_node
