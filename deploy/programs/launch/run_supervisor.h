#pragma once
// One run of a scenario as processes: the monitor, one agent per UAV (and with vehicle.interface = px4 one
// swa_px4_bridge per UAV), the simulator; the agents and bridges supervised and restarted when they crash; everything
// stopped and reaped at the end. The launcher's main() calls this once, or twice for --compare.

#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

#include "launch_options.h"
#include "swa/sim/scenario.h"

namespace swa::launch {

struct Binaries {
  std::string sim, agent, monitor, bridge;  // bridge: swa_px4_bridge, for vehicle.interface = px4
};

struct RunSpec {
  std::string label;          // "swa", "standalone", ...: monitor label
  std::filesystem::path dir;  // outputs; logs in dir/logs
  sim::Scenario scenario;     // the effective scenario: written to dir/scenario.yaml, which every child reads
  std::string origin;         // where it came from, for the file's header: "FILE --set k=v ..."
};

struct RunOutcome {
  int monitor_status = 3;  // 0 PASS, 1 FAIL, 3 INCOMPLETE (also when the monitor itself failed)
  int sim_status = -1;
  int restarts = 0;                          // of agents
  int bridge_restarts = 0;                   // of autopilot bridges (vehicle.interface = px4)
  bool interrupted = false;                  // SIGINT / SIGTERM or --timeout-s
  std::string verdict;                       // the monitor's verdict line from summary.json, if any
  std::vector<std::string> verdict_reasons;  // why it did not pass, from summary.json
};

// Returns when every child has exited; `stop` (SIGINT / SIGTERM) ends the run early. Throws std::runtime_error only
// when nothing could be started (e.g. the output directory is not writable); failures of children are reported in the
// outcome.
RunOutcome superviseRun(const LaunchOptions& options, const Binaries& bin, int domain, const RunSpec& spec,
                        const std::atomic<bool>& stop);

}  // namespace swa::launch
