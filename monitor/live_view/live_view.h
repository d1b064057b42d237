#pragma once
// What swa_monitor --live publishes, fed by the monitor node as its inputs arrive: the swarm at each truth sample (at
// most every 50 ms of wall time: a lockstep run goes faster than anyone watches), each agent's states, the metrics of
// each scored step (live_messages.h, metrics_json.h), through the LiveServer.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "live_server.h"
#include "monitor_inputs.h"
#include "swa/monitor/summary_format.h"

namespace swa::live {

// The page served at "/" (page/index.html, compiled in).
const std::string& livePage();

class LiveView {
 public:
  // Starts the server (LiveServer::Options::page is the live page). Throws LiveError.
  LiveView(const std::string& address, int port);

  int port() const { return server_.port(); }
  void onTruth(const monitor_node::TruthSample& truth);
  void onState(const monitor_node::StateSample& state);
  // The rows of a growing time series (LiveRun::series()) not sent yet.
  void onMetrics(const std::vector<monitor::TimeSeriesRow>& series);
  LiveServer::Stats stats() const { return server_.stats(); }

 private:
  LiveServer server_;
  std::uint32_t swarm_channel_ = 0;
  std::uint32_t metrics_channel_ = 0;
  std::map<int, std::uint32_t> state_channels_;
  std::map<int, monitor_node::StateSample> latest_;
  std::optional<std::chrono::steady_clock::time_point> last_swarm_;
  std::size_t metrics_sent_ = 0;
};

}  // namespace swa::live
