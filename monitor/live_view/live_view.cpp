#include "live_view.h"

#include <algorithm>
#include <cmath>

#include "live_messages.h"
#include "metrics_json.h"

namespace swa::live {
namespace {

constexpr auto kSwarmPeriod = std::chrono::milliseconds(50);

LiveServer::Options serverOptions(const std::string& address, int port) {
  LiveServer::Options o;
  o.address = address;
  o.port = port;
  o.page = livePage();
  return o;
}

std::uint64_t nanoseconds(double t_s) { return static_cast<std::uint64_t>(std::llround(std::max(t_s, 0.0) * 1e9)); }

}  // namespace

LiveView::LiveView(const std::string& address, int port) : server_(serverOptions(address, port)) {
  swarm_channel_ = server_.addChannel(kSwarmTopic, kSwarmSchemaName, swarmJsonSchema());
  metrics_channel_ = server_.addChannel(monitor_node::kMetricsTopic, monitor_node::kMetricsSchemaName,
                                        monitor_node::metricsJsonSchema());
}

void LiveView::onTruth(const monitor_node::TruthSample& truth) {
  const auto now = std::chrono::steady_clock::now();
  if (last_swarm_ && now - *last_swarm_ < kSwarmPeriod) return;
  last_swarm_ = now;
  server_.publish(swarm_channel_, static_cast<std::uint64_t>(std::max<std::int64_t>(truth.stamp_ns, 0)),
                  swarmJson(truth, latest_));
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
    server_.publish(metrics_channel_, nanoseconds(row.t_s), monitor_node::metricsJson(row));
  }
}

}  // namespace swa::live
