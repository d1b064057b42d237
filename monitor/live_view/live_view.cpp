#include "live_view.h"

#include <algorithm>
#include <cmath>

#include "live_messages.h"
#include "step_metrics_json.h"

namespace swa::live {
namespace {

constexpr auto kSwarmPeriod = std::chrono::milliseconds(50);
// The plots roll over a minute: twice a second moves them by under 1 % of their width, and costs the monitor about
// 1.3 ms of CPU a second (BENCHMARKS.md).
constexpr auto kPlotsPeriod = std::chrono::milliseconds(500);

LiveServer::Options serverOptions(const std::string& address, int port) {
  LiveServer::Options o;
  o.address = address;
  o.port = port;
  o.page = livePage();
  return o;
}

std::uint64_t nanoseconds(double t_s) { return static_cast<std::uint64_t>(std::llround(std::max(t_s, 0.0) * 1e9)); }

}  // namespace

LiveView::LiveView(const std::string& address, int port, const monitor::MetricsConfig& scoring)
    : server_(serverOptions(address, port)), scoring_(scoring) {
  swarm_channel_ = server_.addChannel(kSwarmTopic, kSwarmSchemaName, swarmJsonSchema());
  metrics_channel_ = server_.addChannel(monitor_node::kMetricsTopic, monitor_node::kMetricsSchemaName,
                                        monitor_node::stepMetricsJsonSchema());
  swarm_picture_channel_ = server_.addChannel(kSwarmPictureTopic, kPictureSchemaName, pictureJsonSchema());
  metric_pictures_channel_ = server_.addChannel(kMetricPicturesTopic, kPicturesSchemaName, picturesJsonSchema());
}

void LiveView::onTruth(const monitor_node::TruthSample& truth) {
  const auto now = std::chrono::steady_clock::now();
  if (last_swarm_ && now - *last_swarm_ < kSwarmPeriod) {
    held_truth_ = truth;
    return;
  }
  last_swarm_ = now;
  held_truth_.reset();
  publishSwarm(swarmScene(truth, latest_), truth.stamp_ns);
}

void LiveView::publishSwarm(const SwarmScene& scene, std::int64_t stamp_ns) {
  const auto stamp = static_cast<std::uint64_t>(std::max<std::int64_t>(stamp_ns, 0));
  server_.publish(swarm_channel_, stamp, swarmJson(scene));
  server_.publish(swarm_picture_channel_, stamp, pictureJson(scene.t_s, swarmSvg(scene, frame_.follow(scene))));
}

void LiveView::publishPlots() {
  plots_held_ = false;
  last_plots_ = std::chrono::steady_clock::now();
  const double t_s = window_.rows().empty() ? 0.0 : window_.rows().back().t_s;
  server_.publish(metric_pictures_channel_, nanoseconds(t_s), picturesJson(t_s, metricPictures(window_, scoring_)));
}

void LiveView::flush() {
  if (held_truth_) {
    publishSwarm(swarmScene(*held_truth_, latest_), held_truth_->stamp_ns);
    held_truth_.reset();
  }
  if (plots_held_) publishPlots();
}

void LiveView::onState(const monitor_node::StateSample& state) {
  if (state.uav < 0) return;
  latest_[state.uav] = state;
  auto channel = state_channels_.find(state.uav);
  if (channel == state_channels_.end()) {
    channel = state_channels_
                  .emplace(state.uav, server_.addChannel(agentStateTopic(state.uav), kAgentStateSchemaName,
                                                         agentStateJsonSchema()))
                  .first;
  }
  server_.publish(channel->second, static_cast<std::uint64_t>(std::max<std::int64_t>(state.stamp_ns, 0)),
                  agentStateJson(state));
}

void LiveView::onMetrics(const std::vector<monitor::TimeSeriesRow>& series) {
  for (; metrics_sent_ < series.size(); ++metrics_sent_) {
    const monitor::TimeSeriesRow& row = series[metrics_sent_];
    server_.publish(metrics_channel_, nanoseconds(row.t_s), monitor_node::stepMetricsJson(row));
    window_.add(row);
    plots_held_ = true;
  }
  if (plots_held_ && (!last_plots_ || std::chrono::steady_clock::now() - *last_plots_ >= kPlotsPeriod)) {
    publishPlots();
  }
}

}  // namespace swa::live
