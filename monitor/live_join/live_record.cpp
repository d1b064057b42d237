#include "live_record.h"

namespace swa::monitor_node {

RunEnd endFromEvent(const EventRecord& end_event) {
  if (end_event.text == "completed") return {true, "completed"};
  return {false, "simulator ended the scenario: " + (end_event.text.empty() ? "no reason given" : end_event.text)};
}

std::vector<std::pair<std::string, std::uint64_t>> inputCounts(const LiveRun& run) {
  const JoinCounters& c = run.joinCounters();
  return {
      {"truth_samples", c.truth_samples},
      {"state_samples", c.state_samples},
      {"dropped_truth_out_of_order", c.truth_out_of_order},
      {"dropped_truth_duplicate", c.truth_duplicate},
      {"dropped_truth_malformed", c.truth_malformed},
      {"dropped_state_unknown_uav", c.state_unknown_uav},
      {"dropped_state_duplicate", c.state_duplicate},
      {"dropped_state_late", c.state_late},
      {"dropped_state_unmatched", c.state_unmatched},
      {"dropped_events_unknown_kind", run.unknownEvents()},
      {"dropped_steps_rejected", run.rejectedSteps()},
      {"truth_nonfinite_uavs", c.truth_nonfinite_uavs},
      {"state_nonfinite", c.state_nonfinite},
      {"steps_incomplete", c.steps_incomplete},
      {"missing_states", c.missing_states},
      {"truth_missed_ms", static_cast<std::uint64_t>(run.coverage().missedSeconds() * 1e3 + 0.5)},
  };
}

RunRecord makeRunRecord(const LiveRun& run, const LiveRunConfig& config, const RunContext& context) {
  RunRecord r;
  r.mode = run.mode() ? agent::toString(*run.mode()) : "unknown";
  r.label = context.label.empty() ? r.mode : context.label;
  r.scenario = context.scenario;
  r.seed = context.seed;
  r.completed = context.end.completed;
  r.end_reason = context.end.reason;
  r.scoring = run.metricsConfig();
  r.scoring.radius_tolerance = context.tolerance;
  r.scoring.window_start_s = run.windowStartS();
  r.summary = run.summary();
  r.verdict = record::judge({r.completed, r.end_reason, run.sawTruth(), r.summary, r.scoring, run.coverage().missed(),
                             run.failsafeNow(), run.outOfControlNow(), config.failure_hint});
  r.counts = inputCounts(run);
  r.restarts = context.restarts;
  r.events = run.events();
  r.series = run.series();
  r.trajectories = run.trajectories();
  return r;
}

}  // namespace swa::monitor_node
