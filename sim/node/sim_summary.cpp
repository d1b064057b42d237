#include "sim_summary.h"

#include <nlohmann/json.hpp>

#include <cstdio>

namespace swa::sim_node {

const char* clockModeName(sim::ClockMode mode) { return mode == sim::ClockMode::kLockstep ? "lockstep" : "realtime"; }

std::string summaryJson(const SimSummary& summary, const sim::Scenario& scenario) {
  const LatencyReport& l = summary.latency;
  // Members in this order; NaN (a statistic of an empty set) is written as null.
  const nlohmann::ordered_json j{
      {"completed", summary.completed},
      {"clock_mode", clockModeName(scenario.clock.mode)},
      {"uav_count", scenario.uav_count},
      {"seed", scenario.seed},
      {"steps", summary.steps},
      {"sim_time_s", summary.sim_time_s},
      {"wall_time_s", summary.wall_time_s},
      {"discovery_s", summary.discovery_s},
      {"handshake_s", summary.handshake_s},
      {"collisions", summary.collisions},
      {"applied_commands", summary.applied_commands},
      {"ignored_commands", summary.ignored_commands},
      {"refused_commands", summary.refused_commands},
      {"refused_writers", summary.refused_writers},
      {"command_handovers", summary.command_handovers},
      {"unacknowledged_sensor_steps", summary.unacknowledged_sensor_steps},
      {"unacknowledged_clock_steps", summary.unacknowledged_clock_steps},
      {"agent_dead_events", summary.agent_dead_events},
      {"agent_rejoined_events", summary.agent_rejoined_events},
      {"stalls", summary.stalls},
      {"stalled_s", summary.stalled_s},
      {"reconnections", summary.reconnections},
      {"resent_after_reconnection", summary.resent_after_reconnection},
      {"dead_at_end", summary.dead_at_end},
      {"write_failures", summary.write_failures},
      {"latency_commands_judged", l.published},
      {"latency_commands_answered", l.answered},
      {"latency_p50_us", l.p50_us},
      {"latency_p99_us", l.p99_us},
      {"latency_max_us", l.max_us},
      {"latency_mean_us", l.mean_us},
      {"latency_quantile_resolution", LogHistogram::relativeResolution()},
      {"late_commands", l.late},
      {"late_fraction", l.lateFraction()},
      {"missing_answers", l.missing},
      {"missing_fraction", l.missingFraction()},
      {"duplicate_answers", l.duplicates},
      {"unmatched_answers", l.unmatched},
      {"step_lag_p99_us", summary.step_lag_p99_us},
      {"step_lag_max_us", summary.step_lag_max_us},
  };
  return j.dump(2) + "\n";
}

std::string summaryLine(const SimSummary& s, const sim::Scenario& scenario) {
  char line[1024];
  std::snprintf(line, sizeof line,
                "swa_sim: %s %s run of %d UAVs: %lld steps, %.1f s sim in %.2f s wall (x%.1f), %d collision(s), "
                "%llu dead / %llu rejoined agent event(s), %llu ignored command(s); loop latency over %llu command(s): "
                "p50 %.0f us, p99 %.0f us, max %.0f us; %llu late (%.2f %%), %llu missing (%.2f %%)\n",
                s.completed ? "completed" : "INTERRUPTED", clockModeName(scenario.clock.mode), scenario.uav_count,
                static_cast<long long>(s.steps), s.sim_time_s, s.wall_time_s,
                s.wall_time_s > 0 ? s.sim_time_s / s.wall_time_s : 0.0, s.collisions,
                static_cast<unsigned long long>(s.agent_dead_events),
                static_cast<unsigned long long>(s.agent_rejoined_events),
                static_cast<unsigned long long>(s.ignored_commands),
                static_cast<unsigned long long>(s.latency.answered), s.latency.p50_us, s.latency.p99_us,
                s.latency.max_us, static_cast<unsigned long long>(s.latency.late), 100.0 * s.latency.lateFraction(),
                static_cast<unsigned long long>(s.latency.missing), 100.0 * s.latency.missingFraction());
  return line;
}

}  // namespace swa::sim_node
