#include <algorithm>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "csv_text.h"
#include "run_files.h"

namespace swa::monitor_node {
namespace {

JsonValue stringArray(const std::vector<std::string>& items) {
  JsonValue a = JsonValue::array();
  for (const std::string& s : items) a.push(JsonValue::string(s));
  return a;
}

JsonValue restartJson(const AgentRestart& r) {
  JsonValue o = JsonValue::object();
  o.set("wall_s", JsonValue::number(r.wall_s));
  o.set("uav", JsonValue::integer(r.uav));
  o.set("exit_status", JsonValue::string(r.exit_status));
  o.set("restart_count", JsonValue::integer(r.restart_count));
  o.set("backoff_s", JsonValue::number(r.backoff_s));
  return o;
}

JsonValue eventJson(const EventRecord& e) {
  JsonValue o = JsonValue::object();
  o.set("t_s", JsonValue::number(e.t_s));
  o.set("kind", JsonValue::string(e.kind));
  o.set("uav", JsonValue::integer(e.uav));
  o.set("other_uav", JsonValue::integer(e.other_uav));
  o.set("value", JsonValue::number(e.value));
  o.set("text", JsonValue::string(e.text));
  return o;
}

}  // namespace

JsonValue summaryJson(const RunRecord& run) {
  JsonValue j = JsonValue::object();
  j.set("label", JsonValue::string(run.label));
  j.set("mode", JsonValue::string(run.mode));
  j.set("scenario", run.scenario.empty() ? JsonValue() : JsonValue::string(run.scenario));
  j.set("seed", run.seed ? JsonValue::unsignedInteger(*run.seed) : JsonValue());
  j.set("completed", JsonValue::boolean(run.completed));
  j.set("end_reason", JsonValue::string(run.end_reason));
  j.set("verdict", JsonValue::string(toString(run.verdict.outcome)));
  j.set("verdict_reasons", stringArray(run.verdict.reasons));
  j.set("formation_radius_m", JsonValue::number(run.formation_radius_m));
  j.set("tolerance", JsonValue::number(run.tolerance));
  j.set("collision_distance_m", JsonValue::number(run.collision_distance_m));
  j.set("window_from_s", JsonValue::number(run.window_start_s));
  // The same keys and values as swa_batch's per-seed entries (monitor::toJson(Summary)).
  for (const monitor::NamedValue& f : monitor::summaryFields(run.summary)) j.set(f.key, JsonValue::number(f.value));
  const auto monitor_restarts = static_cast<std::size_t>(
      std::count_if(run.restarts.restarts.begin(), run.restarts.restarts.end(),
                    [](const AgentRestart& r) { return r.uav == AgentRestart::kMonitor; }));
  j.set("agent_restarts", JsonValue::unsignedInteger(run.restarts.restarts.size() - monitor_restarts));
  j.set("monitor_restarts", JsonValue::unsignedInteger(monitor_restarts));
  j.set("restarts_malformed_rows", JsonValue::integer(run.restarts.malformed_rows));
  j.set("restarts_problems", stringArray(run.restarts.problems));
  JsonValue restarts = JsonValue::array();
  for (const AgentRestart& r : run.restarts.restarts) restarts.push(restartJson(r));
  j.set("restarts", std::move(restarts));
  for (const auto& [key, count] : run.counts) j.set(key, JsonValue::unsignedInteger(count));
  JsonValue events = JsonValue::array();
  for (const EventRecord& e : run.events) events.push(eventJson(e));
  j.set("events", std::move(events));
  return j;
}

std::string timeSeriesCsv(const std::vector<monitor::TimeSeriesRow>& series) {
  std::string out = monitor::csvHeader() + "\n";
  for (const monitor::TimeSeriesRow& row : series) out += monitor::formatCsvRow(row) + "\n";
  return out;
}

std::string trajectoriesCsv(const std::vector<monitor::UavTrajectory>& trajectories) {
  std::string out = std::string(trajectoriesHeader()) + "\n";
  for (const monitor::UavTrajectory& t : trajectories) {
    for (const monitor::TrajectoryPoint& p : t.points) {
      out += monitor::formatNumber(p.t_s) + "," + std::to_string(t.id) + "," + monitor::formatNumber(p.x_m) + "," +
             monitor::formatNumber(p.y_m) + "\n";
    }
  }
  return out;
}

std::string eventsCsv(const std::vector<EventRecord>& events) {
  std::string out = std::string(eventsHeader()) + "\n";
  for (const EventRecord& e : events) {
    out += monitor::formatNumber(e.t_s) + "," + csvField(e.kind) + "," + std::to_string(e.uav) + "," +
           std::to_string(e.other_uav) + "," + monitor::formatNumber(e.value) + "," + csvField(e.text) + "\n";
  }
  return out;
}

void writeRunFiles(const std::string& dir, const RunRecord& run) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw RunFileError("cannot create " + dir + ": " + ec.message());
  const auto write = [&dir](const char* name, const std::string& content) {
    const fs::path path = fs::path(dir) / name;
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file << content;
    file.close();
    if (!file) throw RunFileError("cannot write " + path.string());
  };
  write(kSummaryFile, summaryJson(run).dump());
  write(kTimeSeriesFile, timeSeriesCsv(run.series));
  write(kTrajectoriesFile, trajectoriesCsv(run.trajectories));
  write(kEventsFile, eventsCsv(run.events));
}

}  // namespace swa::monitor_node
