#pragma once
// How the simulator advances the world: in lockstep with the agents (lockstep_driver.h) or paced by the wall clock
// (realtime_driver.h), both around the same ports (sim_ports.h). What they share: who is alive (for the truth), and
// what a stall of the simulator itself does to the deadlines (swa/app/stall_watch.h).

#include <atomic>
#include <chrono>

#include "latency_stats.h"
#include "sim_options.h"
#include "sim_ports.h"
#include "sim_summary.h"
#include "swa/app/stall_watch.h"
#include "swa/sim/scenario.h"
#include "swa/sim/world.h"

namespace swa::sim_node {

// What a driver works on, all owned by the SimNode that owns the driver.
struct DriverContext {
  const sim::Scenario& scenario;
  const SimOptions& options;
  sim::World& world;
  SimPorts& ports;
  SimSummary& summary;
  const std::atomic<bool>& stop;
};

class Driver {
 public:
  using Clock = SimPorts::Clock;

  explicit Driver(const DriverContext& context);
  virtual ~Driver() = default;
  Driver(const Driver&) = delete;
  Driver& operator=(const Driver&) = delete;

  // Publishes the first step and runs the world to its end, or until stop is requested.
  virtual void run() = 0;
  // Whether the agent of `uav` answers (the truth says so; dead agents' UAVs hover on the simulator's failsafe).
  virtual bool alive(int uav) const = 0;
  // Realtime: how late the simulator stepped against its schedule (empty in lockstep).
  const LogHistogram& stepLag() const { return step_lag_; }

 protected:
  // Longest single wait in a loop, so a stop is noticed quickly.
  static constexpr auto kPollPeriod = std::chrono::milliseconds(100);
  // How long an unanswered step's samples wait before they are sent again, where that is needed
  // (SimPorts::repeatWhileWaiting): far longer than an answer takes (about a millisecond), far shorter than the agent
  // timeout.
  static constexpr auto kRepeatPeriod = std::chrono::milliseconds(50);

  // Logs and counts a stall of the simulator itself; no commander could be heard meanwhile, and one that outlasted
  // the DDS lease gives the agents time to find the simulator again (reconnect_grace_until_).
  void noteStall(Clock::duration lost, Clock::time_point now);
  SimPorts::AliveFn aliveFn() const {
    return [this](int uav) { return alive(uav); };
  }

  const sim::Scenario& scenario_;
  const SimOptions& options_;
  sim::World& world_;
  SimPorts& ports_;
  SimSummary& summary_;
  const std::atomic<bool>& stop_;
  const int n_;
  app::StallWatch stall_;
  Clock::time_point reconnect_grace_until_{};
  LogHistogram step_lag_;
};

}  // namespace swa::sim_node
