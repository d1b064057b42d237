#include "live_run.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <utility>

namespace swa::monitor_node {

LiveRun::LiveRun(const LiveRunConfig& config)
    : config_(config),
      joiner_(config.join_horizon, config.join_grace_s),
      metrics_(config.metrics),
      trajectories_(config.trajectory_period_s),
      mode_(config.mode) {}

void LiveRun::onTruth(TruthSample truth) {
  joiner_.addTruth(std::move(truth));
  for (const JoinedStep& step : joiner_.takeReady()) score(step);
}

void LiveRun::onState(int topic_uav, StateSample state) {
  // A state on UAV i's topic that names UAV j is not trusted for either (uav -1 never matches a truth entry).
  if (state.uav != topic_uav) state.uav = -1;
  if (!mode_ && state.mode) mode_ = state.mode;
  joiner_.addState(state);
  for (const JoinedStep& step : joiner_.takeReady()) score(step);
}

void LiveRun::tick(double wall_s) {
  joiner_.advanceClock(wall_s);
  for (const JoinedStep& step : joiner_.takeReady()) score(step);
}

void LiveRun::onEvent(EventRecord event) {
  if (event.kind == event_kind::kGnssLost) {
    if (event.uav == kAllUavs && !gnss_lost_all_s_) gnss_lost_all_s_ = event.t_s;
    if (!gnss_lost_any_s_ || event.t_s < *gnss_lost_any_s_) gnss_lost_any_s_ = event.t_s;
  }
  if (event.kind == event_kind::kScenarioEnd && !end_event_) end_event_ = event;
  events_.push_back(std::move(event));
}

std::vector<record::ControlLoss> LiveRun::outOfControlNow() const {
  std::map<int, const EventRecord*> last;  // each UAV's newest control event
  for (const EventRecord& e : events_) {
    if (e.kind != event_kind::kControlLost && e.kind != event_kind::kControlRegained) continue;
    const EventRecord*& newest = last[e.uav];
    if (newest == nullptr || e.t_s >= newest->t_s) newest = &e;
  }
  std::vector<record::ControlLoss> out;
  for (const auto& [uav, e] : last) {
    if (e->kind == event_kind::kControlLost) out.push_back({uav, e->t_s, e->text});
  }
  return out;
}

void LiveRun::finish() {
  for (const JoinedStep& step : joiner_.flush()) score(step);
}

void LiveRun::score(const JoinedStep& step) {
  coverage_.add(step.truth.stamp_ns);
  monitor::StepInput input;
  input.stamp_ns = step.truth.stamp_ns;
  input.uavs = step.truth.uavs;
  if (config_.score_estimates) {
    input.estimates.reserve(step.states.size());
    for (const std::optional<StateSample>& s : step.states) {
      input.estimates.push_back(s ? s->estimate : monitor::EstimateRecord{});
    }
  }
  try {
    const monitor::StepMetrics& m = metrics_.add(input);
    series_.push_back(monitor::toRow(m));
    status_.any_step = true;
    status_.t_s = m.t_s;
    status_.d_nb_m = m.geometry.mean_neighbor_distance_m;
    status_.min_sep_m = m.geometry.min_separation_m;
    status_.collisions = m.collisions;
    status_.groups = m.geometry.groups;
  } catch (const std::invalid_argument&) {
    // The joiner already enforces increasing stamps and unique ids; this guards the accumulator's own rules.
    ++rejected_steps_;
    return;
  }
  ++steps_;
  status_.uavs = static_cast<int>(step.truth.uavs.size());
  status_.live_agents =
      static_cast<int>(std::count(step.truth.agent_alive.begin(), step.truth.agent_alive.end(), true));
  failsafe_now_.clear();
  for (std::size_t k = 0; k < step.truth.uavs.size(); ++k) {
    if (!step.truth.agent_alive[k]) failsafe_now_.push_back(step.truth.uavs[k].id);
  }
  trajectories_.add(stampSeconds(input.stamp_ns), input.uavs);
  if (config_.window_from_events) replay_.push_back(std::move(input));
}

void LiveRun::onMission(const agent::MissionCommand& command) {
  const double at_s = joiner_.newestTruth() ? stampSeconds(*joiner_.newestTruth()) : 0.0;
  const monitor::ReplannedMission r =
      monitor::replanMission(config_.metrics.mission_legs, config_.metrics.mission_start_s, at_s, command);
  config_.metrics.mission_legs = r.legs;
  config_.metrics.mission_start_s = r.start_s;
  metrics_.replanMission(r.legs, r.start_s);
}

double LiveRun::windowStartS() const {
  if (!config_.window_from_events) return config_.metrics.window_start_s;
  if (gnss_lost_all_s_) return *gnss_lost_all_s_;
  if (gnss_lost_any_s_) return *gnss_lost_any_s_;
  return 0.0;
}

monitor::Summary LiveRun::summary() const {
  if (!config_.window_from_events) return metrics_.summary();
  monitor::MetricsConfig mc = config_.metrics;
  mc.window_start_s = windowStartS();
  monitor::MetricsAccumulator replay(mc);
  for (const monitor::StepInput& input : replay_) replay.add(input);
  return replay.summary();
}

std::vector<EventRecord> LiveRun::events() const {
  std::vector<EventRecord> sorted = events_;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const EventRecord& a, const EventRecord& b) { return a.t_s < b.t_s; });
  return sorted;
}

}  // namespace swa::monitor_node
