// What a run's directory holds before its children start (run_files.h): apart from the supervisor, which only handles
// processes.

#include "run_files.h"

#include <fstream>
#include <stdexcept>
#include <system_error>

#include "swa/agent/config_io.h"
#include "swa/sim/scenario_io.h"

namespace swa::launch {

std::string scenarioFile(const RunSpec& spec) { return (spec.dir / "scenario.yaml").string(); }

std::string agentConfigFile(const RunSpec& spec) { return (spec.dir / "agent.yaml").string(); }

void prepareRunDirectory(const RunSpec& spec, const std::filesystem::path& logs) {
  std::error_code ec;
  std::filesystem::remove_all(logs, ec);  // logs of an earlier run in the same directory would be appended to
  for (const char* stale : {"summary.json", "sim_summary.json"}) std::filesystem::remove(spec.dir / stale, ec);
  std::filesystem::create_directories(logs);
  // The one configuration of the run: every child reads this file (no --set), so the directory holds exactly
  // what ran.
  std::ofstream config(scenarioFile(spec));
  config << "# The effective scenario of this run, written by swa_launch from " << spec.origin << "\n"
         << sim::scenarioToYaml(spec.scenario);
  // Each agent reads its own section, as the simulator implies it (agent.formation.radius_m from the spacing, ...):
  // the agent needs no scenario parser.
  std::ofstream agents(agentConfigFile(spec));
  agents << "# The agents' configuration of this run, written by swa_launch from " << spec.origin << "\n"
         << agent::toYaml(spec.scenario.agent);
  std::ofstream restarts(logs / "restarts.csv");
  restarts << "wall_s,uav,exit_status,restart_count,backoff_s\n";
  if (!config.flush() || !agents.flush() || !restarts.flush())
    throw std::runtime_error("cannot write into " + spec.dir.string());
}

}  // namespace swa::launch
