#pragma once
// The monitor's metrics of one scored step as a JSON message, and the JSON Schema of those messages: the channel
// /swa/monitor/metrics of a recording (and of the live view). Field names and units are timeseries.csv's columns; a
// value that is not defined at a step (NaN in the CSV) is null.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "swa/monitor/summary_format.h"
#include "swa/recording/recording.h"

namespace swa::monitor_node {

constexpr const char* kMetricsTopic = "/swa/monitor/metrics";
constexpr const char* kMetricsSchemaName = "swa_monitor/StepMetrics";

std::string stepMetricsJsonSchema();
std::string stepMetricsJson(const monitor::TimeSeriesRow& row);

// Writes the rows of a growing time series (LiveRun::series()) to the metrics channel of a recording, each once,
// with the step's time as log time.
class MetricsRecorder {
 public:
  explicit MetricsRecorder(recording::Recording& recording) : recording_(recording) {}
  void writeNew(const std::vector<monitor::TimeSeriesRow>& series);

 private:
  recording::Recording& recording_;
  std::optional<std::uint16_t> channel_;
  std::size_t written_ = 0;
};

}  // namespace swa::monitor_node
