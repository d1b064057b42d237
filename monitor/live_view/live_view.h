#pragma once
// What swa_monitor --live publishes, fed by the monitor node as its inputs arrive: the swarm at each truth sample and
// its picture (at most every 50 ms of wall time: a lockstep run goes faster than anyone watches), each agent's
// states, the metrics of each scored step and their plots over the last minute (at most every 500 ms)
// (live_messages.h, step_metrics_json.h, live_pictures.h), through the LiveServer.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "live_pictures.h"
#include "live_server.h"
#include "monitor_inputs.h"
#include "swa/monitor/summary_format.h"

namespace swa::live {

// The page served at "/" (page/index.html, compiled in).
const std::string& livePage();

class LiveView {
 public:
  // Starts the server (LiveServer::Options::page is the live page). `scoring` gives the plots their bands and lines.
  // Throws LiveError.
  LiveView(const std::string& address, int port, const monitor::MetricsConfig& scoring);

  int port() const { return server_.port(); }
  void onTruth(const monitor_node::TruthSample& truth);
  void onState(const monitor_node::StateSample& state);
  // The rows of a growing time series (LiveRun::series()) not sent yet.
  void onMetrics(const std::vector<monitor::TimeSeriesRow>& series);
  // Publishes what the wall-time limits held back: the newest swarm and plots (the end of a run).
  void flush();
  LiveServer::Stats stats() const { return server_.stats(); }

 private:
  void publishSwarm(const SwarmScene& scene, std::int64_t stamp_ns);
  void publishPlots();

  LiveServer server_;
  monitor::MetricsConfig scoring_;
  std::uint32_t swarm_channel_ = 0;
  std::uint32_t metrics_channel_ = 0;
  std::uint32_t swarm_picture_channel_ = 0;
  std::uint32_t metric_pictures_channel_ = 0;
  SwarmFrame frame_;
  MetricWindow window_;
  std::optional<monitor_node::TruthSample> held_truth_;  // the newest truth not published (wall-time limit)
  bool plots_held_ = false;
  std::optional<std::chrono::steady_clock::time_point> last_plots_;
  std::map<int, std::uint32_t> state_channels_;
  std::map<int, monitor_node::StateSample> latest_;
  std::optional<std::chrono::steady_clock::time_point> last_swarm_;
  std::size_t metrics_sent_ = 0;
};

}  // namespace swa::live
