#pragma once
// The end of a live run: why it ended, and the RunRecord (summary, verdict, files' content) built from the LiveRun.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "live_run.h"
#include "swa/run_record/run_record.h"

namespace swa::monitor_node {

using record::RestartLog;
using record::RunRecord;

struct RunEnd {
  bool completed = false;  // EVENT_SCENARIO_END with text "completed"
  std::string reason;      // "completed", or why not (shown in the report and summary.json)
};

// The end event's meaning: the simulator writes "completed" when the scenario ran to its duration, anything else
// ("interrupted", "discovery timeout", ...) when it did not.
RunEnd endFromEvent(const EventRecord& end_event);

struct RunContext {
  std::string label;     // empty: the mode
  std::string scenario;  // scenario file, empty without
  std::optional<std::uint64_t> seed;
  double tolerance = monitor::kDefaultRadiusTolerance;
  RunEnd end;
  RestartLog restarts;
};

// The input counters of summary.json, in order; keys starting with "dropped_" are inputs thrown away.
std::vector<std::pair<std::string, std::uint64_t>> inputCounts(const LiveRun& run);

// Call after LiveRun::finish().
RunRecord makeRunRecord(const LiveRun& run, const LiveRunConfig& config, const RunContext& context);

}  // namespace swa::monitor_node
