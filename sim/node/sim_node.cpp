#include "sim_node.h"

#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "lockstep_driver.h"
#include "realtime_driver.h"
#include "swa/app/cpu_time.h"
#include "swa/sim/timing.h"

namespace swa::sim_node {

SimNode::SimNode(const sim::Scenario& scenario, const SimOptions& options, int domain_id,
                 const std::string& profiles_file)
    : scenario_(scenario),
      options_(options),
      world_(scenario_),
      ports_(scenario_, options_, world_, summary_, stop_, domain_id, profiles_file) {
  const DriverContext context{scenario_, options_, world_, ports_, summary_, stop_};
  if (scenario_.clock.mode == sim::ClockMode::kLockstep) {
    driver_ = std::make_unique<LockstepDriver>(context);
  } else {
    driver_ = std::make_unique<RealtimeDriver>(context);
  }
}

SimNode::~SimNode() = default;

int SimNode::run() {
  if (ports_.awaitDiscovery()) {
    const auto started = SimPorts::Clock::now();
    driver_->run();
    finish(started);
  } else if (!summary_.refused_as_twin) {  // a refused twin publishes nothing: the running one owns the topics
    if (stop_) std::fprintf(stderr, "swa_sim: interrupted before the first step\n");
    ports_.publishEndBeforeStart(stop_ ? "interrupted before start" : "discovery timeout");
  }
  writeSummaryFile();
  std::fprintf(stderr, "%s\n", app::cpuTimeLine("swa_sim").c_str());
  return summary_.completed ? 0 : 1;
}

void SimNode::writeSummaryFile() const {
  if (options_.summary_out.empty()) return;
  std::ofstream out(options_.summary_out);
  out << summaryJson(summary_, scenario_);
  if (!out.flush()) std::fprintf(stderr, "swa_sim: cannot write --summary-out %s\n", options_.summary_out.c_str());
}

void SimNode::finish(SimPorts::Clock::time_point started) {
  summary_.completed = world_.finished() && !stop_;
  summary_.wall_time_s = secondsSince(started) - summary_.handshake_s;
  ports_.finishLatency(scenario_.clock.mode == sim::ClockMode::kRealtime, driver_->stepLag());
  summary_.steps = world_.step_index();
  summary_.sim_time_s = sim::stampSeconds(world_.time_ns());
  summary_.collisions = world_.collisions();
  for (int i = 0; i < world_.uav_count(); ++i) {
    if (!driver_->alive(i)) summary_.dead_at_end.push_back(i);
  }
  ports_.publishEnd([this](int uav) { return driver_->alive(uav); }, summary_.completed);
  std::fputs(summaryLine(summary_, scenario_).c_str(), stderr);
}

}  // namespace swa::sim_node
