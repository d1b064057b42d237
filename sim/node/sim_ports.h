#pragma once
// The simulator's DDS side, shared by its lockstep and realtime drivers: publishes each UAV's sensor samples on its
// own topics (with vehicle.interface = px4 or ardupilot the attitude as the autopilot's, autopilot_vehicles.h) and the
// world's truth, events and clock, and collects the agents' setpoints (one commander per UAV, swa/dds/command_gate.h;
// their loop latency, latency_stats.h). Owns the participant and every endpoint. Message contents come from the wire
// bridge (idl/wire); which step to publish and when is the driver's. The sensor writers are sensor_ports.h's, the
// world's writers world_ports.h's; the commands are read in sim_commands.cpp, the deaf port healed in port_healing.cpp.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <swa/msg/VelocitySetpoint.h>

#include "answer.h"
#include "ardupilot_vehicles.h"
#include "latency_stats.h"
#include "port_clock.h"
#include "px4_vehicles.h"
#include "sensor_ports.h"
#include "sim_options.h"
#include "sim_summary.h"
#include "swa/dds/command_gate.h"
#include "swa/dds/deaf_port_watch.h"
#include "swa/dds/participant.h"
#include "swa/dds/sample_queue.h"
#include "swa/sim/world.h"
#include "world_ports.h"

namespace swa::sim_node {

class SimPorts {
 public:
  using Clock = PortClock;
  using AliveFn = std::function<bool(int uav)>;

  using Answer = sim_node::Answer;

  // Creates every DDS entity (throws swa::dds::DdsError) and opens --truth-out (throws std::runtime_error).
  SimPorts(const sim::Scenario& scenario, const SimOptions& options, sim::World& world, SimSummary& summary,
           const std::atomic<bool>& stop, int domain_id, const std::string& profiles_file);
  ~SimPorts();

  // Until every agent's endpoints (and --wait-monitors readers of truth and events) are matched, the startup timeout
  // passes, stop is requested, or an older simulator runs in this swarm (summary.refused_as_twin). True: all matched.
  bool awaitDiscovery();

  void publishStepOutputs(const AliveFn& alive);  // the world's events, truth when due, the clock
  // The clock tick of the current step; sent again while a lockstep run waits (agent/node/world_pause.h).
  void publishClock() { world_ports_.publishClock(); }
  // `due`: when the UAVs' next IMU samples are due (realtime), for the latency statistics; nullopt in lockstep.
  // With `due` every IMU sample is written before the step's detections and GNSS fixes, without it after them (the
  // reasons are at the definition). Returns the IMU stamp published to each UAV (nullopt: none this step).
  std::vector<std::optional<agent::StampNs>> publishSensors(std::optional<Clock::time_point> due);
  // An event of the node (agent dead / rejoined, scenario end) at the current sim time.
  void publishEvent(const char* kind, int uav, double value, const std::string& text) {
    world_ports_.publishEvent(kind, uav, value, text);
  }
  // The end event of a run that never started (discovery timeout, interrupted), and a moment for it to arrive.
  void publishEndBeforeStart(const std::string& why) { world_ports_.publishEndBeforeStart(why); }
  // The last truth (unless published at this step), the end event, then a moment for late readers.
  void publishEnd(const AliveFn& alive, bool completed) { world_ports_.publishEnd(alive, completed); }

  // Setpoints received within `wait` that come from their UAV's commander and name their UAV; the others are counted
  // (refused, ignored) and dropped. Their loop latency is recorded while timing is on.
  const std::vector<Answer>& drain(Clock::duration wait);
  void apply(const Answer& a);  // to the world (an autopilot interface: to the UAV's autopilot)
  // Before the world steps: with an autopilot interface, what each autopilot flies (autopilot_vehicles.h); else
  // nothing.
  void vehiclesStep();
  // Lockstep, while waiting for `uavs`' answers: with an autopilot interface their attitude once more (PX4 streams
  // it; best effort may have lost it); else, once after a reconnection (healDeafness), the step's samples again (the
  // sensors are reliable, but the writers that sent them were deleted).
  void repeatWhileWaiting(const std::vector<int>& uavs);
  void timeLatency(bool on) { time_latency_ = on; }
  // Realtime: the next step takes the commands drained up to `t`; an answer received later missed it (late).
  void stepTaken(Clock::time_point t);
  // Whether every UAV's newest IMU sample has been answered (true while latency is not timed).
  bool newestAnswered() const { return !time_latency_ || latency_.newestAnswered(); }
  void finishLatency(bool realtime, const LogHistogram& step_lag);
  // The simulator did not run for `lost`: no commander could be heard meanwhile.
  void shiftCommanders(Clock::duration lost, Clock::time_point now) { gate_.shift(lost, now); }

  // Lockstep: whether detections or a GNSS fix went to `uav` this step, and whether its reader acknowledged them.
  bool sideWritten(int uav) const { return sensors_.sideWritten(uav); }
  bool detectionsAcknowledged(int uav, double wait_s) { return sensors_.detectionsAcknowledged(uav, wait_s); }
  bool gnssAcknowledged(int uav, double wait_s) { return sensors_.gnssAcknowledged(uav, wait_s); }
  bool clockAcknowledged(double wait_s) { return world_ports_.clockAcknowledged(wait_s); }

 private:
  // Whether `a` comes from the UAV's current commander (admitted at `at`); refusals counted and reported.
  bool fromCommander(const Answer& a, Clock::time_point at);
  void admit(Answer&& a);                   // an answer of the commander: checked, timed, into admitted_
  std::string commandTopic(int uav) const;  // where a UAV's setpoints come from (for the log)
  bool olderTwinRuns();                     // another swa_sim older than us in this swarm: refuse (logged)
  void noteYoungerTwins();
  // The participant and every endpoint (the stand-ins' apart), at the start and when re-created.
  void connect(int domain_id, const std::string& profiles_file);
  std::vector<std::string> unmatchedEndpoints() const;  // readable, e.g. "swa/uav2/imu (no reader)"
  // When this process no longer hears one of its shared-memory ports (deaf_port_watch.h; a peer re-created the port
  // while the simulator was stopped), it re-creates its participant and waits until every endpoint matched again
  // (reconnect). With autopilot stand-ins it only says so.
  void healDeafness();
  void reconnect();
  // Agents find a new participant within about a second (a stopped simulator's agents may themselves be re-creating
  // theirs); beyond this the run goes on and the unanswered are declared dead as usual.
  static constexpr auto kRematchTimeout = std::chrono::seconds(20);

  const sim::Scenario& scenario_;
  const SimOptions& options_;
  sim::World& world_;
  SimSummary& summary_;
  const std::atomic<bool>& stop_;
  const int n_;
  dds::CommandGate gate_;
  CommandLatencyTracker latency_;
  bool time_latency_ = true;
  WorldPorts world_ports_;  // opens --truth-out: a bad one stops the simulator before it joins the domain
  SensorPorts sensors_;
  std::vector<Answer> batch_;
  std::vector<Answer> admitted_;
  std::vector<std::optional<Answer>> refused_;  // per UAV, the newest refused answer (CommandGate::releasable)

  // The queue outlives the participant, whose listeners push into it.
  dds::SampleQueue<Answer> queue_;
  std::unique_ptr<dds::Participant> participant_;
  std::string profiles_file_;
  bool frames_allowed_ = true;
  bool resend_after_reconnect_ = false;
  dds::DeafPortWatch deaf_ports_;  // with stand-ins, each deaf port is said once
  // vehicle.interface = px4 or ardupilot: instead of the IMU writers (sensor_ports.h) and cmd_.
  std::unique_ptr<AutopilotVehicles> autopilot_;
  std::vector<dds::Reader<msg::VelocitySetpoint>> cmd_;
};

}  // namespace swa::sim_node
