#pragma once
// The simulated world as a Fast DDS node: a thin adapter around swa::sim::World. Publishes each UAV's sensor samples
// on its own topics, reads the agents' setpoints, steps the world in lockstep with the agents (or in real time),
// and publishes ground truth, scenario events and the clock. No model code here: the world is sim::World, the
// lockstep bookkeeping is lockstep.h.

#include <chrono>
#include <cstdint>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <swa/msg/Clock.h>
#include <swa/msg/Detections.h>
#include <swa/msg/GnssFix.h>
#include <swa/msg/Imu.h>
#include <swa/msg/ScenarioEvent.h>
#include <swa/msg/SwarmTruth.h>
#include <swa/msg/VelocitySetpoint.h>

#include "command_gate.h"
#include "latency_stats.h"
#include "lockstep.h"
#include "sim_options.h"
#include "stall_watch.h"
#include "swa/dds/participant.h"
#include "swa/dds/sample_queue.h"
#include "swa/sim/scenario.h"
#include "swa/record/events.h"
#include "swa/sim/world.h"

namespace swa::sim_node {

struct SimSummary {
  bool completed = false;        // reached the scenario's duration (false: interrupted)
  std::int64_t steps = 0;
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;      // from the first step to the end (discovery and the realtime handshake excluded)
  double discovery_s = 0.0;
  double handshake_s = 0.0;      // realtime: from publishing step 0 until every agent answered it
  int collisions = 0;
  std::uint64_t applied_commands = 0;
  std::uint64_t ignored_commands = 0;  // stale, duplicate, or naming the wrong UAV
  // Commands from a second writer on a UAV's cmd_vel while its current one is active (command_gate.h), and how many
  // such writers were seen; changes of a UAV's writer after its first (a restarted agent).
  std::uint64_t refused_commands = 0;
  std::size_t refused_writers = 0;
  std::uint64_t command_handovers = 0;
  bool refused_as_twin = false;  // an older simulator runs in this swarm: this one did not start
  std::uint64_t unacknowledged_sensor_steps = 0;  // lockstep: detections / GNSS not acknowledged in time
  std::uint64_t agent_dead_events = 0;
  std::uint64_t agent_rejoined_events = 0;
  // Times the simulator itself did not run for longer than its loop explains (stall_watch.h), and for how long in
  // all: its wall-clock deadlines were moved by it, nobody was declared dead for it.
  int stalls = 0;
  double stalled_s = 0.0;
  std::vector<int> dead_at_end;
  std::uint64_t write_failures = 0;
  // Loop latency: wall time from publishing a UAV's IMU sample to receiving the cmd_vel that answers it (its
  // answered_seq / answered_stamp_ns), taken in the reader's listener. Late (realtime only): received after the UAV's
  // next IMU sample was due. Missing: never answered although that deadline passed (lockstep: never answered).
  LatencyReport latency;
  // Realtime only: how late the simulator itself stepped and published against its wall-clock schedule (us; NaN in
  // lockstep). A large lag means the simulator thread, not the agents, is what falls behind.
  double step_lag_p99_us = 0.0;
  double step_lag_max_us = 0.0;
};

class SimNode {
 public:
  // Creates every DDS entity; throws swa::dds::DdsError. Opens --truth-out (throws std::runtime_error).
  SimNode(const sim::Scenario& scenario, const SimOptions& options, int domain_id, const std::string& profiles_file);
  ~SimNode();

  // Waits for discovery, runs the scenario, publishes EVENT_SCENARIO_END. Returns the process exit status.
  int run();
  const SimSummary& summary() const { return summary_; }
  std::string summaryJson() const;

 private:
  using Clock = std::chrono::steady_clock;
  struct Answer {
    int uav = 0;  // whose cmd_vel reader received it
    msg::VelocitySetpoint setpoint;
    Clock::time_point received;  // when the listener got it (not when this thread drained it)
    dds::WriterGuid writer{};
  };

  bool awaitDiscovery();
  void runLockstep();
  void runRealtime();
  void publishStepOutputs();  // world events, truth (when due), clock
  // `due`: when the UAVs' next IMU samples are due (realtime), for the latency statistics; nullopt in lockstep.
  std::vector<std::optional<agent::StampNs>> publishSensors(std::optional<Clock::time_point> due);
  void publishTruth();
  // An event of this node (agent dead / rejoined, scenario end) at the current sim time, or one of the world's.
  void publishEvent(const char* kind, int uav, double value, const std::string& text);
  void publishEvent(const record::EventRecord& event);
  // Moves `deadline` by any stall of the simulator seen while waiting.
  void awaitSensorAcks(Clock::time_point& deadline);

  void drainLockstep(Clock::duration wait);
  void drainRealtime(Clock::duration wait);
  void collectLateAnswers(Clock::time_point until);  // realtime, after the last step: statistics only
  void recordLatency(const Answer& a);
  void finishLatency();
  void apply(const Answer& a);
  bool fromCommander(const Answer& a);  // the UAV's current commander (command_gate.h); refusals counted, reported
  bool olderTwinRuns();                 // another swa_sim older than us in this swarm: refuse (logged)
  void noteYoungerTwin();
  bool agentAlive(int uav) const;

  sim::Scenario scenario_;
  SimOptions options_;
  sim::World world_;
  int n_;
  LockstepTracker lockstep_;
  CommandGate gate_;
  dds::PeerKey reported_twin_{};
  StallWatch stall_;
  void noteStall(Clock::duration lost, Clock::time_point now);  // logs and counts a stall of the simulator itself
  Clock::time_point reconnect_grace_until_{};  // after a lease-long stall: agents may need until then to reconnect
  SimSummary summary_;
  CommandLatencyTracker latency_;
  LogHistogram step_lag_;
  bool time_latency_ = true;  // false during the realtime handshake (step 0)

  // Realtime liveness.
  std::vector<bool> rt_alive_;
  std::vector<Clock::time_point> rt_last_answer_;
  std::vector<std::optional<agent::StampNs>> rt_last_applied_;

  std::vector<std::uint32_t> imu_seq_, det_seq_, gnss_seq_;
  std::vector<bool> side_written_;  // detections or GNSS published to that UAV this step
  std::uint32_t truth_seq_ = 0, event_seq_ = 0, clock_seq_ = 0;
  std::int64_t last_truth_step_ = -1;
  std::ofstream truth_csv_;
  std::vector<Answer> batch_;

  // The queue outlives the participant, whose listeners push into it.
  dds::SampleQueue<Answer> queue_;
  std::unique_ptr<dds::Participant> participant_;
  std::vector<dds::Writer<msg::Imu>> imu_;
  std::vector<dds::Writer<msg::Detections>> det_;
  std::vector<dds::Writer<msg::GnssFix>> gnss_;
  std::vector<dds::Reader<msg::VelocitySetpoint>> cmd_;
  dds::Writer<msg::SwarmTruth> truth_;
  dds::Writer<msg::ScenarioEvent> events_;
  dds::Writer<msg::Clock> clock_;
};

}  // namespace swa::sim_node
