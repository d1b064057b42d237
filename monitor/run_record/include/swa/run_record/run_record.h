#pragma once
// One run as its directory records it (run_dir.h): who ran, how it ended, its verdict, its summary metrics, input
// counters, restarts, events, time series and trajectories. Written by swa_monitor and swa_batch, read by
// swa_monitor --combine, swa_launch and the tests.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "swa/monitor/accumulator.h"
#include "swa/monitor/report_html.h"
#include "swa/monitor/summary_format.h"
#include "swa/run_record/restarts.h"
#include "swa/run_record/verdict.h"
#include "swa/sim/events.h"

namespace swa::record {

struct RunRecord {
  std::string label;                  // report column / legend name
  std::string mode;                   // "swa", "standalone", "anchored", or "unknown"
  std::string scenario;               // scenario file; empty without one
  std::optional<std::uint64_t> seed;  // the scenario's seed; nullopt without a scenario
  bool completed = false;             // EVENT_SCENARIO_END "completed" received
  std::string end_reason;             // "completed", or why not
  Verdict verdict;
  // What the run was scored against: r and its PASS band, the collision distance, and the metrics window's start as
  // the run used it (the GNSS loss time when there is one)
  monitor::MetricsConfig scoring;
  monitor::Summary summary;
  // Input counters in summary.json order ("truth_samples", "dropped_truth_out_of_order", ...): keys starting with
  // "dropped_" are inputs thrown away.
  std::vector<std::pair<std::string, std::uint64_t>> counts;
  RestartLog restarts;
  std::vector<sim::EventRecord> events;
  std::vector<monitor::TimeSeriesRow> series;
  std::vector<monitor::UavTrajectory> trajectories;
};

}  // namespace swa::record
