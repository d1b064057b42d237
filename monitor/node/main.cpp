// swa_monitor: swarm metrics, verdict and report of a run over Fast DDS, or the combined report of several runs.
// See --help (monitor_options.cpp).

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include "combine.h"
#include "live_config.h"
#include "live_mode.h"
#include "monitor_options.h"
#include "swa/app/program.h"
#include "swa/dds/options.h"
#include "swa/monitor/output_dir.h"
#include "swa/sim/scenario_io.h"

namespace swa::monitor_node {
namespace {

app::Plan prepare(const std::vector<std::string>& args) {
  const MonitorOptions options = parseMonitorOptions(args);
  if (auto done = app::printIf(options.help, monitorUsage)) return *done;
  if (options.combineMode()) return app::exitWith(runCombine(options, std::cout, std::cerr));
  std::optional<sim::Scenario> scenario;
  if (!options.scenario_path.empty()) scenario = sim::loadScenario(options.scenario_path, options.overrides);
  LiveRunConfig config = scenario ? liveRunConfig(*scenario) : liveRunConfigWithoutScenario();
  config.join_grace_s = 2.0;  // several heartbeat repair rounds of a lost state (the node ticks the wall clock)
  const int domain = dds::resolveDomain(options.domain);
  monitor::prepareOutputDir(options.out_dir);
  return app::startWith(
      [options, scenario, config, domain]() -> std::unique_ptr<app::Role> {
        return std::make_unique<LiveMode>(options, scenario, config, domain);
      },
      kExitBadInput);
}

}  // namespace
}  // namespace swa::monitor_node

int main(int argc, char** argv) {
  return swa::app::runProgram("swa_monitor", "scenario", argc, argv, swa::monitor_node::prepare);
}
