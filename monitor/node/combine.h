#pragma once
// swa_monitor --combine: one report.html (and a combined summary.json) from run directories written by live
// monitors, e.g. the paper's SWA-vs-standalone comparison on one seed. No DDS: only files.

#include <ostream>

#include "monitor_options.h"

namespace swa::monitor_node {

// Reads every LABEL=DIR (run_files.h readRunDir), writes into options.out_dir:
//   summary.json  {"runs": [each run's summary.json object, "label" set to its LABEL]}
//   report.html   one column per run (+ the .svg plots)
// Returns the exit status: the FIRST run's verdict (0 / 1 / 3), or kExitBadInput when an argument, the scenario
// or an input file is bad, or the output cannot be written (message on `err`, naming the file).
int runCombine(const MonitorOptions& options, std::ostream& out, std::ostream& err);

}  // namespace swa::monitor_node
