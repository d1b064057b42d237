#pragma once
// Command line of swa_monitor. Parsing is separate from main() so it can be tested; every problem is reported at
// once. The launcher relies on these exact options and on the exit codes below (documented in monitorUsage()).

#include <optional>
#include <string>
#include <vector>

#include "swa/monitor/report_html.h"
#include "swa/recording/record_set.h"

namespace swa::monitor_node {

// Exit status of swa_monitor, live and --combine.
enum ExitCode : int {
  kExitPass = 0,        // scenario completed, formation held (verdict.h)
  kExitFail = 1,        // completed, but a verdict criterion failed
  kExitBadInput = 2,    // bad arguments, scenario or (--combine) unreadable run directory: nothing started
  kExitIncomplete = 3,  // the scenario did not complete (interrupted, timeout, no truth, sim reported a failure)
};

struct CombineInput {
  std::string label;  // column name in the combined report
  std::string dir;    // a run directory written by a live swa_monitor
};

struct MonitorOptions {
  std::string out_dir = "out/monitor";  // --out DIR
  bool out_given = false;
  std::string scenario_path;           // --scenario FILE (optional in both modes)
  std::vector<std::string> overrides;  // --set key=value, in order (needs --scenario)
  std::string label;                   // --label NAME (default: the agents' mode)
  std::optional<std::string> domain;   // --domain D (else SWA_DOMAIN, else 0)
  std::string restarts_path;           // --restarts FILE (launcher's restart log, read at the end)
  double timeout_s = 0.0;              // --timeout-s S: wall seconds without EVENT_SCENARIO_END; 0 = none
  double tolerance = monitor::kDefaultRadiusTolerance;  // --tolerance F: PASS needs |d_NB - r| <= F r
  bool tolerance_given = false;
  std::string record_path;                                       // --record FILE.mcap: empty, no recording
  recording::RecordSet record_set = recording::RecordSet::kAll;  // --record-set SET: which topics it holds
  std::optional<std::string> live_address;  // --live [ADDR:]PORT: the live view (nullopt: none); ADDR 127.0.0.1
  int live_port = 0;
  bool quiet = false;                 // --quiet: no status line
  std::vector<CombineInput> combine;  // --combine LABEL=DIR [LABEL=DIR]...: offline mode
  bool help = false;

  bool combineMode() const { return !combine.empty(); }
};

// Accepts "--opt value" and "--opt=value"; after --combine, further arguments up to the next option are more
// LABEL=DIR entries. Throws std::invalid_argument listing every problem, one per line.
MonitorOptions parseMonitorOptions(const std::vector<std::string>& args);
std::string monitorUsage();

}  // namespace swa::monitor_node
