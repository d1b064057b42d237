#pragma once
// Everything the live monitor does with its inputs, without DDS: truth, states and events go in (in arrival
// order, from one thread), joined steps go through monitor::MetricsAccumulator in stamp order, and out come the
// time series, trajectories, events and summary of the run. The DDS node (monitor_node.h) only converts messages
// and calls this; tests drive it directly.

#include <cstdint>
#include <optional>
#include <vector>

#include "monitor_inputs.h"
#include "step_joiner.h"
#include "swa/agent/config.h"
#include "swa/monitor/accumulator.h"
#include "swa/monitor/report_html.h"
#include "swa/monitor/summary_format.h"
#include "truth_coverage.h"

namespace swa::monitor_node {

struct LiveRunConfig {
  // The agents' formation (radius, circle fit: the state message carries neither) and how the run is scored;
  // window_start_s is used as given unless window_from_events is set.
  monitor::MetricsConfig metrics;
  // Without a scenario the window start is not known up front: it is the stamp of the first EVENT_GNSS_LOST for
  // all UAVs, else of the first one for any UAV, else 0. The summary is then computed at the end by replaying the
  // stored steps (the per-step metrics do not depend on the window, so the live time series is final).
  bool window_from_events = false;
  // false: no NEES at all (standalone agents estimate in their take-off frame, nothing to score; as swa_batch).
  bool score_estimates = true;
  std::string failure_hint;         // record::Scoring's, said with a FAIL verdict
  std::optional<agent::Mode> mode;  // the scenario's; without one, the first mode an agent reports
  // StepJoiner horizon, in truth samples (10 Hz): 3 s. A state lost on the way is repaired by the reliable protocol
  // after the writer's next heartbeat (100 ms) and holds back that agent's later states until then; with 30 % loss
  // each repair round (heartbeat, acknack, data) gets through only about one time in three, so a step must wait
  // seconds, not the 0.5 s it used to (measured: 10 % loss left 401 of 401 steps incomplete with 5).
  int join_horizon = 30;
  // ... and at least this much wall time (LiveRun::tick) after the step's truth arrived: in lockstep 30 samples
  // pass in about 0.1 s, less than one repair round of a lost state on a busy host.
  double join_grace_s = 0.0;
  double trajectory_period_s = 0.5;
};

// The latest scored step, for the status line.
struct LiveStatus {
  bool any_step = false;
  double t_s = 0.0;
  double d_nb_m = monitor::kNaN;
  double min_sep_m = monitor::kNaN;
  std::uint64_t collisions = 0;
  int groups = 0;
  int live_agents = 0;  // agents the truth calls alive
  int uavs = 0;
};

class LiveRun {
 public:
  // Throws std::invalid_argument on a bad metrics config or horizon.
  explicit LiveRun(const LiveRunConfig& config);

  void onTruth(TruthSample truth);
  // `topic_uav`: the UAV whose state topic delivered it; a sample naming another UAV is dropped as unknown.
  void onState(int topic_uav, StateSample state);
  void onEvent(EventRecord event);
  void onUnknownEvent() { ++unknown_events_; }  // an event kind this build does not know: dropped, counted
  // A mission from the ground (already through the one-writer gate): from the newest truth's time on, the run is
  // scored against the plan every agent now flies (monitor::replanMission), and the record says that plan.
  void onMission(const agent::MissionCommand& command);
  // The wall clock (monotonic seconds) the join grace is measured on; releases the steps it makes overdue.
  void tick(double wall_s);
  // Scores every step still waiting for states. Further inputs after finish() are still accepted.
  void finish();

  // Whether the join has nothing pending (all truth so far scored).
  bool joinIdle() const { return joiner_.idle(); }
  std::optional<agent::StampNs> newestTruth() const { return joiner_.newestTruth(); }
  bool sawTruth() const { return steps_ > 0; }
  const LiveStatus& status() const { return status_; }
  // The UAVs whose agent the last scored step's truth calls dead (on failsafe), by id.
  const std::vector<int>& failsafeNow() const { return failsafe_now_; }
  // The vehicles whose last control event is a loss (record::ControlLoss), by UAV.
  std::vector<record::ControlLoss> outOfControlNow() const;
  // The first EVENT_SCENARIO_END received.
  const std::optional<EventRecord>& endEvent() const { return end_event_; }

  std::optional<agent::Mode> mode() const { return mode_; }
  double windowStartS() const;
  // The scoring as it stands: the configuration's, with the mission the ground changed (onMission).
  const monitor::MetricsConfig& metricsConfig() const { return config_.metrics; }
  monitor::Summary summary() const;
  const std::vector<monitor::TimeSeriesRow>& series() const { return series_; }
  std::vector<monitor::UavTrajectory> trajectories() const { return trajectories_.trajectories(); }
  std::vector<EventRecord> events() const;  // by time, arrival order within a time
  const JoinCounters& joinCounters() const { return joiner_.counters(); }
  std::uint64_t unknownEvents() const { return unknown_events_; }
  std::uint64_t rejectedSteps() const { return rejected_steps_; }
  // The parts of the run (from sim time 0 to the last scored truth) the monitor did not see.
  const TruthCoverage& coverage() const { return coverage_; }

 private:
  void score(const JoinedStep& step);

  LiveRunConfig config_;
  StepJoiner joiner_;
  monitor::MetricsAccumulator metrics_;
  monitor::TrajectoryRecorder trajectories_;
  std::vector<monitor::TimeSeriesRow> series_;
  std::vector<monitor::StepInput> replay_;  // every scored step, only when window_from_events
  std::vector<EventRecord> events_;
  TruthCoverage coverage_;
  std::optional<EventRecord> end_event_;
  std::optional<double> gnss_lost_all_s_;
  std::optional<double> gnss_lost_any_s_;
  std::optional<agent::Mode> mode_;
  LiveStatus status_;
  std::vector<int> failsafe_now_;
  int steps_ = 0;
  std::uint64_t unknown_events_ = 0;
  std::uint64_t rejected_steps_ = 0;
};

}  // namespace swa::monitor_node
