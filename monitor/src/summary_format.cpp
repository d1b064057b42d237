#include "swa/monitor/summary_format.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <system_error>
#include <type_traits>

namespace swa::monitor {
namespace {

void appendCsv(std::string& out, double v) {
  if (!out.empty()) out += ',';
  out += formatNumber(v);
}

// The one list of Summary fields, in declaration order: summaryFields reads through it, summaryFromFields writes
// through it, so the two cannot disagree. `S` is Summary or const Summary.
template <class S, class F>
void visitSummary(S& s, F&& f) {
  f("steps", s.steps);
  f("duration_s", s.duration_s);
  f("window_start_s", s.window_start_s);
  f("window_duration_s", s.window_duration_s);
  f("uav_count", s.uav_count);
  f("mean_neighbor_distance_m", s.mean_neighbor_distance_m);
  f("formation_error_m", s.formation_error_m);
  f("edge_length_m", s.edge_length_m);
  f("min_separation_m", s.min_separation_m);
  f("collisions", s.collisions);
  f("drift_velocity_mps", s.drift_velocity_mps);
  f("drift_velocity_windows_mps", s.drift_velocity_windows_mps);
  f("centroid_displacement_m", s.centroid_displacement_m);
  f("uav_displacement_m", s.uav_displacement_m);
  f("drift_speed_max_mps", s.drift_speed_max_mps);
  f("groups", s.groups);
  f("spread_m", s.spread_m);
  f("anees_position", s.anees_position);
  f("anees_velocity", s.anees_velocity);
  f("anees_agents", s.anees_agents);
  f("anees_band_low", s.anees_band_low);
  f("anees_band_high", s.anees_band_high);
  f("anees_position_in_band", s.anees_position_in_band);
  f("anees_velocity_in_band", s.anees_velocity_in_band);
  f("nees_steps", s.nees_steps);
  f("nees_samples", s.nees_samples);
  f("nees_skipped_unknown_id", s.nees_skipped_unknown_id);
  f("nees_skipped_invalid", s.nees_skipped_invalid);
  f("mission_end_error_m", s.mission_end_error_m);
  f("mission_path_error_m", s.mission_path_error_m);
  f("mission_d_nb_moving_m", s.mission_d_nb_moving_m);
  f("mission_uav_end_error_m", s.mission_uav_end_error_m);
  f("mission_uav_end_spread_m", s.mission_uav_end_spread_m);
}

template <class T>
void assignField(T& field, double value) {
  if constexpr (std::is_floating_point_v<T>) {
    field = value;
  } else {
    if (!std::isfinite(value)) return;
    const double lo = static_cast<double>(std::numeric_limits<T>::lowest());
    // The largest double below max: converting max itself (2^64 for uint64) back to T would overflow.
    const double hi = std::nextafter(static_cast<double>(std::numeric_limits<T>::max()), 0.0);
    field = static_cast<T>(std::clamp(std::round(value), lo, hi));
  }
}

}  // namespace

TimeSeriesRow toRow(const StepMetrics& step) {
  TimeSeriesRow row;
  row.t_s = step.t_s;
  row.d_nb_m = step.geometry.mean_neighbor_distance_m;
  row.centroid_x_m = step.geometry.centroid_m.x();
  row.centroid_y_m = step.geometry.centroid_m.y();
  row.drift_mps = step.drift_mps;
  row.min_sep_m = step.geometry.min_separation_m;
  row.collisions = step.collisions;
  row.spread_m = step.geometry.spread_m;
  row.groups = step.geometry.groups;
  row.formation_error_m = step.geometry.formation_error_m;
  row.nees_pos = step.nees.position;
  row.nees_vel = step.nees.velocity;
  return row;
}

const std::string& csvHeader() {
  static const std::string header =
      "t_s,d_nb_m,centroid_x_m,centroid_y_m,drift_mps,min_sep_m,collisions,spread_m,groups,formation_error_m,"
      "nees_pos,nees_vel";
  return header;
}

std::string formatCsvRow(const TimeSeriesRow& row) {
  std::string out;
  appendCsv(out, row.t_s);
  appendCsv(out, row.d_nb_m);
  appendCsv(out, row.centroid_x_m);
  appendCsv(out, row.centroid_y_m);
  appendCsv(out, row.drift_mps);
  appendCsv(out, row.min_sep_m);
  out += ',' + std::to_string(row.collisions);
  appendCsv(out, row.spread_m);
  out += ',' + std::to_string(row.groups);
  appendCsv(out, row.formation_error_m);
  appendCsv(out, row.nees_pos);
  appendCsv(out, row.nees_vel);
  return out;
}

std::string formatNumber(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  std::array<char, 32> buf{};
  const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), value);
  if (result.ec != std::errc()) return "nan";  // cannot happen with 32 chars; never print garbage
  return std::string(buf.data(), result.ptr);
}

std::vector<NamedValue> summaryFields(const Summary& s) {
  std::vector<NamedValue> out;
  visitSummary(s, [&out](const char* key, const auto& value) { out.push_back({key, static_cast<double>(value)}); });
  return out;
}

Summary summaryFromFields(const std::vector<NamedValue>& fields) {
  Summary s;
  visitSummary(s, [&fields](const char* key, auto& field) {
    for (const NamedValue& f : fields) {
      if (f.key == key) {
        assignField(field, f.value);
        return;
      }
    }
  });
  return s;
}

const Statistic* Aggregate::find(std::string_view key) const {
  for (const Statistic& s : metrics) {
    if (s.key == key) return &s;
  }
  return nullptr;
}

Aggregate aggregate(const std::vector<std::vector<NamedValue>>& runs) {
  Aggregate agg;
  agg.runs = static_cast<int>(runs.size());
  std::map<std::string, std::size_t> index;
  std::vector<std::vector<double>> values;
  for (const std::vector<NamedValue>& run : runs) {
    for (const NamedValue& f : run) {
      auto it = index.find(f.key);
      if (it == index.end()) {
        it = index.emplace(f.key, agg.metrics.size()).first;
        agg.metrics.push_back(Statistic{f.key});
        values.emplace_back();
      }
      if (std::isfinite(f.value)) values[it->second].push_back(f.value);
    }
  }
  for (std::size_t k = 0; k < agg.metrics.size(); ++k) {
    Statistic& st = agg.metrics[k];
    const std::vector<double>& v = values[k];
    st.runs = static_cast<int>(v.size());
    if (v.empty()) continue;
    double sum = 0.0;
    st.min = v.front();
    st.max = v.front();
    for (const double x : v) {
      sum += x;
      st.min = std::min(st.min, x);
      st.max = std::max(st.max, x);
    }
    st.mean = sum / static_cast<double>(v.size());
    double sq = 0.0;
    for (const double x : v) sq += (x - st.mean) * (x - st.mean);
    st.std = v.size() > 1 ? std::sqrt(sq / static_cast<double>(v.size() - 1)) : 0.0;
  }
  return agg;
}

Aggregate aggregate(const std::vector<Summary>& runs) {
  std::vector<std::vector<NamedValue>> fields;
  fields.reserve(runs.size());
  for (const Summary& s : runs) fields.push_back(summaryFields(s));
  return aggregate(fields);
}

}  // namespace swa::monitor
