#pragma once
// The simulated world as a Fast DDS process role: a thin adapter around swa::sim::World. Its ports (sim_ports.h)
// publish each UAV's sensor samples and the world's truth, events and clock, and collect the agents' setpoints; its
// driver steps the world in lockstep with the agents or in real time (driver.h). No model code here.

#include <atomic>
#include <memory>
#include <string>

#include "driver.h"
#include "sim_options.h"
#include "sim_ports.h"
#include "sim_summary.h"
#include "swa/app/program.h"
#include "swa/sim/scenario.h"
#include "swa/sim/world.h"

namespace swa::sim_node {

class SimNode : public app::Role {
 public:
  // Creates every DDS entity; throws swa::dds::DdsError. Opens --truth-out (throws std::runtime_error).
  SimNode(const sim::Scenario& scenario, const SimOptions& options, int domain_id, const std::string& profiles_file);
  ~SimNode() override;

  // Waits for discovery, runs the scenario, publishes EVENT_SCENARIO_END, writes --summary-out. Returns the exit
  // status: 0 completed, 1 not.
  int run() override;
  void stop() override { stop_ = true; }
  const SimSummary& summary() const { return summary_; }

 private:
  void finish(SimPorts::Clock::time_point started);
  void writeSummaryFile() const;

  const sim::Scenario scenario_;
  const SimOptions options_;
  sim::World world_;
  SimSummary summary_;
  std::atomic<bool> stop_{false};
  SimPorts ports_;
  std::unique_ptr<Driver> driver_;
};

}  // namespace swa::sim_node
