// swa_monitor: swarm metrics, verdict and report of a run over Fast DDS, or the combined report of several runs.
// See --help (monitor_options.cpp).

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "combine.h"
#include "live_config.h"
#include "live_record.h"
#include "live_run.h"
#include "monitor_node.h"
#include "monitor_options.h"
#include "swa/record/restarts.h"
#include "swa/record/run_dir.h"
#include "swa/record/run_report.h"
#include "swa/dds/options.h"
#include "swa/monitor/output_dir.h"
#include "swa/dds/participant.h"
#include "swa/dds/shutdown.h"
#include "swa/sim/scenario_io.h"

// Fast DDS declares a global `namespace dds = eprosima::fastdds::dds;`: stay inside namespace swa so `dds::` is ours.
namespace swa::monitor_node {
namespace {

int writeOutputs(const std::string& dir, const RunRecord& run) {
  try {
    record::writeRunFiles(dir, run);
    const monitor::ReportNotes notes = record::reportNotes({run}, "SWA monitor report — " + run.label);
    const std::vector<std::string> written = monitor::writeReport(dir, record::reportRuns({run}), notes);
    std::printf("swa_monitor: %s\n", record::verdictText(run.verdict).c_str());
    std::printf("swa_monitor: report %s\n", written.front().c_str());
    return record::exitCode(run.verdict.outcome);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "swa_monitor: %s\n", e.what());
    std::printf("swa_monitor: %s (outputs incomplete)\n", record::verdictText(run.verdict).c_str());
    return kExitIncomplete;
  }
}

int monitorMain(int argc, char** argv) {
  // Everything that can be wrong with the arguments, the scenario or the output directory is found before any DDS
  // entity exists.
  MonitorOptions options;
  std::optional<sim::Scenario> scenario;
  LiveRunConfig config;
  int domain = 0;
  try {
    options = parseMonitorOptions(std::vector<std::string>(argv + 1, argv + argc));
    if (options.help) {
      std::fputs(monitorUsage().c_str(), stdout);
      return kExitPass;
    }
    if (options.combineMode()) return runCombine(options, std::cout, std::cerr);
    if (!options.scenario_path.empty()) scenario = sim::loadScenario(options.scenario_path, options.overrides);
    config = scenario ? liveRunConfig(*scenario) : liveRunConfigWithoutScenario();
    config.join_grace_s = 2.0;  // several heartbeat repair rounds of a lost state (the node ticks the wall clock)
    domain = dds::resolveDomain(options.domain);
    monitor::prepareOutputDir(options.out_dir);
  } catch (const params::ConfigError& e) {
    std::fprintf(stderr, "swa_monitor: invalid scenario:\n%s\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "swa_monitor: %s\n(see swa_monitor --help)\n", e.what());
    return kExitBadInput;
  }

  MonitorNodeOptions node_options;
  if (scenario) node_options.uav_count = scenario->uav_count;
  node_options.formation = config.formation;
  node_options.timeout_s = options.timeout_s;
  node_options.quiet = options.quiet;

  dds::installShutdownHandlers();
  LiveRun run(config);
  RunEnd end;
  {
    std::unique_ptr<MonitorNode> node;
    try {
      node = std::make_unique<MonitorNode>(run, node_options, domain, dds::resolveProfilesFile());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "swa_monitor: DDS error: %s\n", e.what());
      return kExitBadInput;
    }
    dds::acceptShutdownSignals();
    try {
      end = node->run();
    } catch (const std::exception& e) {
      end = {false, std::string("monitor error: ") + e.what()};
      std::fprintf(stderr, "swa_monitor: %s\n", end.reason.c_str());
    }
  }  // every DDS entity deleted here: no more input

  run.finish();
  RunContext context;
  context.label = options.label;
  context.scenario = options.scenario_path;
  if (scenario) context.seed = scenario->seed;
  context.tolerance = options.tolerance;
  context.end = end;
  if (!options.restarts_path.empty()) context.restarts = record::readRestartLog(options.restarts_path);
  return writeOutputs(options.out_dir, makeRunRecord(run, config, context));
}

}  // namespace
}  // namespace swa::monitor_node

int main(int argc, char** argv) { return swa::monitor_node::monitorMain(argc, argv); }
