#include "step_metrics_json.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace swa::monitor_node {
namespace {

using Json = nlohmann::ordered_json;

struct Field {
  const char* name;
  const char* meaning;
  double monitor::TimeSeriesRow::*number;  // nullptr: an integer field below
};

// timeseries.csv's columns with a number value, in its order.
const std::vector<Field>& numberFields() {
  using R = monitor::TimeSeriesRow;
  static const std::vector<Field> fields = {
      {"t_s", "simulated time of the step [s]", &R::t_s},
      {"d_nb_m", "mean distance to the neighbours [m]", &R::d_nb_m},
      {"centroid_x_m", "swarm centroid, east [m]", &R::centroid_x_m},
      {"centroid_y_m", "swarm centroid, north [m]", &R::centroid_y_m},
      {"drift_mps", "speed of the centroid [m/s]", &R::drift_mps},
      {"min_sep_m", "smallest distance between two UAVs [m]", &R::min_sep_m},
      {"spread_m", "largest distance from the centroid [m]", &R::spread_m},
      {"formation_error_m", "mean distance from the formation circle [m]", &R::formation_error_m},
      {"nees_pos", "mean position NEES of the agents' estimates", &R::nees_pos},
      {"nees_vel", "mean velocity NEES of the agents' estimates", &R::nees_vel},
  };
  return fields;
}

}  // namespace

std::string stepMetricsJsonSchema() {
  Json properties = Json::object();
  Json required = Json::array();
  for (const Field& f : numberFields()) {
    properties[f.name] = {{"type", Json::array({"number", "null"})}, {"description", f.meaning}};
    required.push_back(f.name);
  }
  properties["collisions"] = {{"type", "integer"}, {"description", "collisions so far"}};
  properties["groups"] = {{"type", "integer"}, {"description", "connected groups of UAVs"}};
  required.push_back("collisions");
  required.push_back("groups");
  const Json schema = {{"title", kMetricsSchemaName},
                       {"description", "swa_monitor's metrics of one scored step (timeseries.csv's columns)"},
                       {"type", "object"},
                       {"properties", properties},
                       {"required", required}};
  return schema.dump();
}

std::string stepMetricsJson(const monitor::TimeSeriesRow& row) {
  Json j = Json::object();
  for (const Field& f : numberFields()) {
    const double v = row.*(f.number);
    j[f.name] = std::isfinite(v) ? Json(v) : Json(nullptr);
  }
  j["collisions"] = row.collisions;
  j["groups"] = row.groups;
  return j.dump();
}

void MetricsRecorder::writeNew(const std::vector<monitor::TimeSeriesRow>& series) {
  if (written_ >= series.size()) return;
  if (!channel_) channel_ = recording_.jsonChannel(kMetricsTopic, kMetricsSchemaName, stepMetricsJsonSchema());
  const auto now_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  for (; written_ < series.size(); ++written_) {
    const monitor::TimeSeriesRow& row = series[written_];
    const auto log_ns = static_cast<std::uint64_t>(std::llround(std::max(row.t_s, 0.0) * 1e9));
    recording_.writeJson(*channel_, stepMetricsJson(row), log_ns, now_ns);
  }
}

}  // namespace swa::monitor_node
