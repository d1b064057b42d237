#pragma once
// One monitored run as it is written to (and read back from) its output directory:
//   summary.json      the fields below (summary keys = monitor::summaryFields, as swa_batch's per-seed entries)
//   timeseries.csv    monitor::csvHeader() rows
//   trajectories.csv  t_s,uav,x_m,y_m (nan,nan: a gap in that UAV's line)
//   events.csv        t_s,kind,uav,other_uav,value,text
// run_files.h writes and reads these files; run_report.h turns runs into report.html.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "monitor_inputs.h"
#include "restart_log.h"
#include "swa/monitor/accumulator.h"
#include "swa/monitor/report.h"
#include "swa/monitor/report_html.h"
#include "verdict.h"

namespace swa::monitor_node {

struct RunRecord {
  std::string label;                  // report column / legend name
  std::string mode;                   // "swa", "standalone", "anchored", or "unknown"
  std::string scenario;               // scenario file; empty without --scenario
  std::optional<std::uint64_t> seed;  // the scenario's seed; nullopt without --scenario
  bool completed = false;             // EVENT_SCENARIO_END "completed" received
  std::string end_reason;             // "completed", or why not
  Verdict verdict;
  double formation_radius_m = 10.0;  // r the run was scored against
  double tolerance = monitor::kDefaultRadiusTolerance;  // PASS band, fraction of r
  double collision_distance_m = 1.5;
  double window_start_s = 0.0;  // metrics window start (the GNSS loss time when there is one)
  monitor::Summary summary;
  // Input counters in summary.json order ("truth_samples", "dropped_truth_out_of_order", ...): keys starting with
  // "dropped_" are inputs thrown away.
  std::vector<std::pair<std::string, std::uint64_t>> counts;
  RestartLog restarts;
  std::vector<EventRecord> events;
  std::vector<monitor::TimeSeriesRow> series;
  std::vector<monitor::UavTrajectory> trajectories;
};

}  // namespace swa::monitor_node
