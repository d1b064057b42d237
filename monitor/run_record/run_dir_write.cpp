#include <algorithm>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "swa/run_record/csv.h"
#include "swa/run_record/run_dir.h"

namespace swa::record {
namespace {

Json restartJson(const AgentRestart& r) {
  const char* process = r.bridge ? "bridge" : r.uav == AgentRestart::kMonitor ? "monitor" : "agent";
  return Json{{"wall_s", r.wall_s},
              {"uav", r.uav},
              {"process", process},
              {"exit_status", r.exit_status},
              {"restart_count", r.restart_count},
              {"backoff_s", r.backoff_s}};
}

Json eventJson(const sim::EventRecord& e) {
  return Json{{"t_s", e.t_s},     {"kind", e.kind}, {"uav", e.uav}, {"other_uav", e.other_uav},
              {"value", e.value}, {"text", e.text}};
}

}  // namespace

Json summaryJson(const RunRecord& run) {
  Json j;
  j["label"] = run.label;
  j["mode"] = run.mode;
  j["scenario"] = run.scenario.empty() ? Json() : Json(run.scenario);
  j["seed"] = run.seed ? Json(*run.seed) : Json();
  j["completed"] = run.completed;
  j["end_reason"] = run.end_reason;
  j["verdict"] = toString(run.verdict.outcome);
  j["verdict_reasons"] = run.verdict.reasons;
  j["formation_radius_m"] = run.scoring.formation.radius_m;
  j["tolerance"] = run.scoring.radius_tolerance;
  j["collision_distance_m"] = run.scoring.collision_distance_m;
  j["window_from_s"] = run.scoring.window_start_s;
  // The same keys and values as swa_batch's per-seed entries.
  j.update(metricsJson(run.summary));
  const auto countIf = [&run](auto pred) {
    return static_cast<std::size_t>(std::count_if(run.restarts.restarts.begin(), run.restarts.restarts.end(), pred));
  };
  const std::size_t monitor_restarts = countIf([](const AgentRestart& r) { return r.uav == AgentRestart::kMonitor; });
  const std::size_t bridge_restarts = countIf([](const AgentRestart& r) { return r.bridge; });
  j["agent_restarts"] = run.restarts.restarts.size() - monitor_restarts - bridge_restarts;
  j["bridge_restarts"] = bridge_restarts;
  j["monitor_restarts"] = monitor_restarts;
  j["restarts_malformed_rows"] = run.restarts.malformed_rows;
  j["restarts_problems"] = run.restarts.problems;
  j["restarts"] = Json::array();
  for (const AgentRestart& r : run.restarts.restarts) j["restarts"].push_back(restartJson(r));
  for (const auto& [key, count] : run.counts) j[key] = count;
  j["events"] = Json::array();
  for (const sim::EventRecord& e : run.events) j["events"].push_back(eventJson(e));
  return j;
}

Json metricsJson(const monitor::Summary& summary) {
  Json j = Json::object();
  for (const monitor::NamedValue& f : monitor::summaryFields(summary)) j[f.key] = f.value;
  return j;
}

Json aggregateJson(const monitor::Aggregate& aggregate) {
  Json metrics = Json::object();
  for (const monitor::Statistic& s : aggregate.metrics) {
    metrics[s.key] = Json{{"runs", s.runs}, {"mean", s.mean}, {"std", s.std}, {"min", s.min}, {"max", s.max}};
  }
  return Json{{"runs", aggregate.runs}, {"metrics", std::move(metrics)}};
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

std::string eventsCsv(const std::vector<sim::EventRecord>& events) {
  std::string out = std::string(eventsHeader()) + "\n";
  for (const sim::EventRecord& e : events) {
    out += monitor::formatNumber(e.t_s) + "," + csvField(e.kind) + "," + std::to_string(e.uav) + "," +
           std::to_string(e.other_uav) + "," + monitor::formatNumber(e.value) + "," + csvField(e.text) + "\n";
  }
  return out;
}

std::string jsonText(const Json& json) { return json.dump(2) + "\n"; }

void writeTextFile(const std::string& path, const std::string& content) {
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file << content;
  file.close();
  if (!file) throw RunFileError("cannot write " + path);
}

void writeRunFiles(const std::string& dir, const RunRecord& run) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw RunFileError("cannot create " + dir + ": " + ec.message());
  const auto path = [&dir](const char* name) { return (fs::path(dir) / name).string(); };
  writeTextFile(path(kSummaryFile), jsonText(summaryJson(run)));
  writeTextFile(path(kTimeSeriesFile), timeSeriesCsv(run.series));
  writeTextFile(path(kTrajectoriesFile), trajectoriesCsv(run.trajectories));
  writeTextFile(path(kEventsFile), eventsCsv(run.events));
}

}  // namespace swa::record
