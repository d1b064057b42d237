#pragma once
// What a run of swa_sim reports: the counters the node, its ports and its driver keep, written as the --summary-out
// JSON and the last log line.

#include <cstdint>
#include <string>
#include <vector>

#include "latency_stats.h"
#include "swa/sim/scenario.h"

namespace swa::sim_node {

struct SimSummary {
  bool completed = false;  // reached the scenario's duration (false: interrupted)
  std::int64_t steps = 0;
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;  // from the first step to the end (discovery and the realtime handshake excluded)
  double discovery_s = 0.0;
  double handshake_s = 0.0;  // realtime: from publishing step 0 until every agent answered it
  int collisions = 0;
  std::uint64_t applied_commands = 0;
  std::uint64_t ignored_commands = 0;  // stale, duplicate, naming the wrong UAV, or with a non-finite number
  // Commands from a second writer on a UAV's cmd_vel while its current one is active (swa/dds/command_gate.h), and how
  // many such writers were seen; changes of a UAV's writer after its first (a restarted agent).
  std::uint64_t refused_commands = 0;
  std::size_t refused_writers = 0;
  std::uint64_t command_handovers = 0;
  bool refused_as_twin = false;                   // an older simulator runs in this swarm: this one did not start
  std::uint64_t unacknowledged_sensor_steps = 0;  // lockstep: detections / GNSS not acknowledged in time
  std::uint64_t unacknowledged_clock_steps = 0;   // lockstep: a monitor more than 10 steps behind at the deadline
  std::uint64_t agent_dead_events = 0;
  std::uint64_t agent_rejoined_events = 0;
  // Times the simulator itself did not run for longer than its loop explains (swa/app/stall_watch.h), and for how
  // long in all: its wall-clock deadlines were moved by it, nobody was declared dead for it.
  int stalls = 0;
  double stalled_s = 0.0;
  // Times it re-created its participant because it no longer heard its shared-memory port (sim_ports.h).
  int reconnections = 0;
  std::uint64_t resent_after_reconnection = 0;  // lockstep: a step's samples sent again to a UAV after one
  std::vector<int> dead_at_end;
  std::uint64_t write_failures = 0;
  // Loop latency: wall time from publishing a UAV's IMU sample to receiving the cmd_vel that answers it (its
  // answered_seq / answered_stamp_ns), taken in the reader's listener. Late (realtime only): missed the step it
  // answers, i.e. received after the UAV's next IMU sample was due and after the simulator took that step. Missing:
  // never answered although that deadline passed (lockstep: never answered).
  LatencyReport latency;
  // Realtime only: how late the simulator itself stepped and published against its wall-clock schedule (us; NaN in
  // lockstep). A large lag means the simulator thread, not the agents, is what falls behind.
  double step_lag_p99_us = 0.0;
  double step_lag_max_us = 0.0;
};

const char* clockModeName(sim::ClockMode mode);

// The --summary-out file: every member above, NaN as null.
std::string summaryJson(const SimSummary& summary, const sim::Scenario& scenario);

// The run's last log line: how it ended, how fast, how many agents died, the loop latency.
std::string summaryLine(const SimSummary& summary, const sim::Scenario& scenario);

}  // namespace swa::sim_node
