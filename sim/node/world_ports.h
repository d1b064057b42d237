#pragma once
// The world's own topics: its truth (and --truth-out's CSV), its events and its clock tick, with their sequence
// numbers. Apart from sim_ports.h, which owns the participant these writers live on and re-creates them with it.

#include <cstdint>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <swa/msg/Clock.h>
#include <swa/msg/ScenarioEvent.h>
#include <swa/msg/SwarmTruth.h>

#include "sim_options.h"
#include "sim_summary.h"
#include "swa/dds/participant.h"
#include "swa/sim/events.h"
#include "swa/sim/scenario.h"
#include "swa/sim/world.h"

namespace swa::sim_node {

class WorldPorts {
 public:
  using AliveFn = std::function<bool(int uav)>;

  // Opens --truth-out (throws std::runtime_error).
  WorldPorts(const sim::Scenario& scenario, const SimOptions& options, const sim::World& world, SimSummary& summary);

  void open(dds::Participant& participant);  // the writers, on a new participant
  // The --wait-monitors readers of truth and events still missing, e.g. "swa/truth (monitor)".
  void unmatched(std::vector<std::string>& missing) const;

  // As SimPorts' methods of the same names.
  void publishStepOutputs(const AliveFn& alive);
  void publishClock();
  void publishEvent(const char* kind, int uav, double value, const std::string& text);
  void publishEndBeforeStart(const std::string& why);
  void publishEnd(const AliveFn& alive, bool completed);
  bool clockAcknowledged(double wait_s) { return clock_.waitForAcknowledgments(wait_s); }

 private:
  void publishTruth(const AliveFn& alive);
  void publishEvent(const sim::EventRecord& event);

  const sim::Scenario& scenario_;
  const SimOptions& options_;
  const sim::World& world_;
  SimSummary& summary_;
  std::uint32_t truth_seq_ = 0, event_seq_ = 0, clock_seq_ = 0;
  std::int64_t last_truth_step_ = -1;
  std::ofstream truth_csv_;
  dds::Writer<msg::SwarmTruth> truth_;
  dds::Writer<msg::ScenarioEvent> events_;
  dds::Writer<msg::Clock> clock_;
};

}  // namespace swa::sim_node
