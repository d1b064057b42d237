#pragma once
// One run of a scenario as processes: the monitor, one agent per UAV, the simulator; the agents supervised and
// restarted when they crash; everything stopped and reaped at the end. The launcher's main() calls this once, or
// twice for --compare.

#include <filesystem>
#include <string>
#include <vector>

#include "launch_options.h"

namespace swa::launch {

struct Binaries {
  std::string sim, agent, monitor;
};

struct RunSpec {
  std::string label;                     // "swa", "standalone", ...: monitor label
  std::filesystem::path dir;             // outputs; logs in dir/logs
  std::vector<std::string> overrides;    // the user's --set list plus the run's own (e.g. agent.mode)
  int uav_count = 0;
  std::string agent_config_yaml;         // written to dir/agent.yaml
};

struct RunOutcome {
  int monitor_status = 3;  // 0 PASS, 1 FAIL, 3 INCOMPLETE (also when the monitor itself failed)
  int sim_status = -1;
  int restarts = 0;
  bool interrupted = false;  // SIGINT / SIGTERM or --timeout-s
  std::string verdict;       // the monitor's verdict line from summary.json, if any
};

// Returns when every child has exited. Throws std::runtime_error only when nothing could be started (e.g. the
// output directory is not writable); failures of children are reported in the outcome.
RunOutcome superviseRun(const LaunchOptions& options, const Binaries& bin, int domain, const RunSpec& spec);

}  // namespace swa::launch
