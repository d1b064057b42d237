#pragma once
// The files swa_launch writes into a run's directory before any child starts. Apart from run_supervisor.cpp, which
// starts, watches and stops processes: these files are what the children read, and what the directory keeps of the run.

#include <filesystem>
#include <string>

#include "run_supervisor.h"

namespace swa::launch {

// The effective scenario (spec.dir/scenario.yaml), which the simulator and the monitor read.
std::string scenarioFile(const RunSpec& spec);
// The agents' section of it (spec.dir/agent.yaml), which each agent reads.
std::string agentConfigFile(const RunSpec& spec);

// Empties `logs` and removes the reports of an earlier run in spec.dir, then writes scenarioFile, agentConfigFile and
// the header of logs/restarts.csv. Throws std::runtime_error when they cannot be written.
void prepareRunDirectory(const RunSpec& spec, const std::filesystem::path& logs);

}  // namespace swa::launch
