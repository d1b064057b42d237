#include "swa/run_record/run_report.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "swa/monitor/svg_plot.h"

namespace swa::record {
namespace {

std::string uavText(int uav) { return uav == sim::kAllUavs ? "all" : std::to_string(uav); }

std::string droppedText(const RunRecord& run) {
  std::string out;
  for (const auto& [key, count] : run.counts) {
    if (key.rfind("dropped_", 0) != 0 || count == 0) continue;
    std::string name = key.substr(8);
    std::replace(name.begin(), name.end(), '_', ' ');
    out += (out.empty() ? "" : ", ") + name + " " + std::to_string(count);
  }
  return out.empty() ? "none" : out;
}

std::string restartsText(const RunRecord& run) {
  std::string out = std::to_string(run.restarts.restarts.size());
  if (run.restarts.malformed_rows > 0) {
    out += " (" + std::to_string(run.restarts.malformed_rows) + " malformed row(s) in the restart log skipped)";
  }
  return out;
}

// A table of the items_of(run) of every run, one row_of(item) each, behind a "run" column when there are several
// runs; at most kMaxTableRows rows. Also returns how many items there were.
template <class ItemsOf, class RowOf>
std::pair<monitor::ReportTable, std::size_t> itemTable(const char* id, const char* title,
                                                       const std::vector<RunRecord>& runs,
                                                       std::initializer_list<const char*> columns, ItemsOf items_of,
                                                       RowOf row_of) {
  monitor::ReportTable t;
  t.id = id;
  t.title = title;
  const bool many = runs.size() > 1;
  if (many) t.columns.push_back("run");
  for (const char* c : columns) t.columns.push_back(c);
  std::size_t total = 0;
  for (const RunRecord& run : runs) {
    for (const auto& item : items_of(run)) {
      if (++total > kMaxTableRows) continue;
      std::vector<std::string> row = row_of(item);
      if (many) row.insert(row.begin(), run.label);
      t.rows.push_back(std::move(row));
    }
  }
  return {std::move(t), total};
}

}  // namespace

std::vector<monitor::RunReport> reportRuns(const std::vector<RunRecord>& runs) {
  std::vector<monitor::RunReport> out;
  for (const RunRecord& r : runs) out.push_back({r.label, r.summary, r.series, r.trajectories, verdictText(r.verdict)});
  return out;
}

monitor::ReportTable eventsTable(const std::vector<RunRecord>& runs) {
  auto [t, total] = itemTable(
      "events", "Scenario events", runs, {"sim time [s]", "event", "UAV", "other UAV", "value", "detail"},
      [](const RunRecord& run) -> const auto& { return run.events; },
      [](const sim::EventRecord& e) -> std::vector<std::string> {
        return {monitor::formatFixed(e.t_s, 2),
                e.kind,
                uavText(e.uav),
                e.other_uav < 0 ? "" : std::to_string(e.other_uav),
                e.value == 0.0 ? "" : monitor::formatReportValue(e.value),
                e.text};
      });
  t.note =
      "As published by the simulator on swa/events, at the sim time they took effect. value: separation [m] of a "
      "collision, setpoint age [s] of a failsafe, agent timeout [s] of a dead agent.";
  if (total > kMaxTableRows) {
    t.note += " Only the first " + std::to_string(kMaxTableRows) + " of " + std::to_string(total) +
              " events are listed; events.csv and summary.json have them all.";
  }
  t.empty_text = "No event received.";
  return t;
}

monitor::ReportTable restartsTable(const std::vector<RunRecord>& runs) {
  auto [t, total] = itemTable(
      "restarts", "Agent, bridge and monitor restarts", runs,
      {"wall time [s]", "UAV", "exit status", "restart count", "backoff [s]"},
      [](const RunRecord& run) -> const auto& { return run.restarts.restarts; },
      [](const AgentRestart& r) -> std::vector<std::string> {
        return {monitor::formatFixed(r.wall_s, 2), restartSubject(r), r.exit_status, std::to_string(r.restart_count),
                monitor::formatFixed(r.backoff_s, 2)};
      });
  int malformed = 0;
  for (const RunRecord& run : runs) malformed += run.restarts.malformed_rows;
  t.note = "From the launcher's restart log; wall time is seconds since the launcher started.";
  if (malformed > 0) t.note += " " + std::to_string(malformed) + " malformed row(s) skipped (see summary.json).";
  if (total > kMaxTableRows) t.note += " Only the first " + std::to_string(kMaxTableRows) + " are listed.";
  t.empty_text = "No restart.";
  return t;
}

monitor::ReportNotes reportNotes(const std::vector<RunRecord>& runs, const std::string& title) {
  monitor::ReportNotes notes;
  notes.title = title;
  if (!runs.empty()) {
    const RunRecord& first = runs.front();
    notes.scenario = first.scenario;
    notes.scoring = first.scoring;
    notes.gnss_loss_s = monitor::gnssLossTime(first.scoring);
  }
  for (const RunRecord& run : runs) {
    if (run.seed && std::find(notes.seeds.begin(), notes.seeds.end(), *run.seed) == notes.seeds.end()) {
      notes.seeds.push_back(*run.seed);
    }
    const std::string prefix = runs.size() > 1 ? run.label + ": " : "";
    notes.extra.push_back({prefix + "Verdict", verdictText(run.verdict)});
    notes.extra.push_back({prefix + "Mode", run.mode});
    notes.extra.push_back({prefix + "End", run.end_reason});
    notes.extra.push_back({prefix + "Agent restarts", restartsText(run)});
    notes.extra.push_back({prefix + "Dropped inputs", droppedText(run)});
  }
  notes.tables.push_back(eventsTable(runs));
  notes.tables.push_back(restartsTable(runs));
  return notes;
}

}  // namespace swa::record
