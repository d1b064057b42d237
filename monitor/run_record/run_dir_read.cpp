#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>

#include "swa/app/number.h"
#include "swa/run_record/csv.h"
#include "swa/run_record/run_dir.h"

namespace swa::record {
namespace {

// Walks the lines of one of our CSV files: checks the header, yields each record's fields with its line number.
class CsvReader {
 public:
  CsvReader(std::istream& in, std::string source, const std::string& header) : in_(in), source_(std::move(source)) {
    std::string line;
    if (!std::getline(in_, line)) fail(1, "empty file, expected the header '" + header + "'");
    if (chompCr(line) != header) fail(1, "header is not '" + header + "'");
    line_no_ = 1;
  }

  // False at the end. Blank lines are skipped.
  bool next(std::vector<std::string>& fields, std::size_t expected) {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_no_;
      const std::string_view text = chompCr(line);
      if (text.empty()) continue;
      auto split = splitCsvLine(text);
      if (!split) fail(line_no_, "unbalanced quotes");
      if (split->size() != expected) {
        fail(line_no_, std::to_string(split->size()) + " fields, expected " + std::to_string(expected));
      }
      fields = std::move(*split);
      return true;
    }
    return false;
  }

  [[noreturn]] void fail(int line, const std::string& what) const {
    throw RunFileError(source_ + ":" + std::to_string(line) + ": " + what);
  }
  int line() const { return line_no_; }

 private:
  std::istream& in_;
  std::string source_;
  int line_no_ = 0;
};

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RunFileError("cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw RunFileError("cannot read " + path);
  return text.str();
}

// A member as a number: NaN when absent, null (how NaN is written) or not a number.
double numberOrNaN(const Json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : monitor::kNaN;
}

template <class T>
T memberOr(const Json& j, const char* key, T fallback) {
  const auto it = j.find(key);
  if (it == j.end()) return fallback;
  if constexpr (std::is_same_v<T, std::string>) {
    return it->is_string() ? it->get<std::string>() : fallback;
  } else {
    return it->is_number_integer() ? it->get<T>() : fallback;
  }
}

std::vector<std::string> strings(const Json& j, const char* key) {
  std::vector<std::string> out;
  if (const auto it = j.find(key); it != j.end() && it->is_array()) {
    for (const Json& item : *it) out.push_back(item.is_string() ? item.get<std::string>() : "");
  }
  return out;
}

}  // namespace

RunRecord runFromSummaryJson(const Json& j, const std::string& source) {
  const auto fail = [&source](const std::string& what) { throw RunFileError(source + ": " + what); };
  if (!j.is_object()) fail("not a JSON object");
  const auto label = j.find("label");
  const auto verdict = j.find("verdict");
  const auto completed = j.find("completed");
  if (label == j.end() || !label->is_string()) fail("no string member 'label'");
  if (verdict == j.end() || !verdict->is_string() || !parseOutcome(verdict->get<std::string>())) {
    fail("no member 'verdict' with PASS, FAIL or INCOMPLETE");
  }
  if (completed == j.end() || !completed->is_boolean()) fail("no boolean member 'completed'");
  RunRecord run;
  run.label = label->get<std::string>();
  run.verdict.outcome = *parseOutcome(verdict->get<std::string>());
  run.completed = completed->get<bool>();
  run.mode = memberOr<std::string>(j, "mode", "unknown");
  run.scenario = memberOr<std::string>(j, "scenario", "");
  if (const auto seed = j.find("seed"); seed != j.end() && seed->is_number_unsigned()) {
    run.seed = seed->get<std::uint64_t>();
  }
  run.end_reason = memberOr<std::string>(j, "end_reason", "");
  run.verdict.reasons = strings(j, "verdict_reasons");
  monitor::MetricsConfig& scoring = run.scoring;
  if (const double r = numberOrNaN(j, "formation_radius_m"); std::isfinite(r)) scoring.formation.radius_m = r;
  if (const double t = numberOrNaN(j, "tolerance"); std::isfinite(t)) scoring.radius_tolerance = t;
  if (const double c = numberOrNaN(j, "collision_distance_m"); std::isfinite(c)) scoring.collision_distance_m = c;
  if (const double w = numberOrNaN(j, "window_from_s"); std::isfinite(w)) scoring.window_start_s = w;

  std::vector<monitor::NamedValue> fields;
  for (const monitor::NamedValue& f : monitor::summaryFields(monitor::Summary{})) {
    fields.push_back({f.key, numberOrNaN(j, f.key.c_str())});
  }
  run.summary = monitor::summaryFromFields(fields);

  run.restarts.found = true;
  run.restarts.malformed_rows = memberOr<int>(j, "restarts_malformed_rows", 0);
  run.restarts.problems = strings(j, "restarts_problems");
  if (const auto restarts = j.find("restarts"); restarts != j.end() && restarts->is_array()) {
    for (const Json& r : *restarts) {
      AgentRestart a;
      a.wall_s = numberOrNaN(r, "wall_s");
      a.uav = memberOr<int>(r, "uav", -1);
      a.exit_status = memberOr<std::string>(r, "exit_status", "");
      a.restart_count = memberOr<std::int64_t>(r, "restart_count", 0);
      a.backoff_s = numberOrNaN(r, "backoff_s");
      run.restarts.restarts.push_back(a);
    }
  }
  for (const auto& [key, value] : j.items()) {
    if (key.rfind("dropped_", 0) == 0 && value.is_number_unsigned())
      run.counts.emplace_back(key, value.get<std::uint64_t>());
  }
  return run;
}

std::vector<monitor::TimeSeriesRow> parseTimeSeriesCsv(std::istream& in, const std::string& source) {
  CsvReader csv(in, source, monitor::csvHeader());
  std::vector<monitor::TimeSeriesRow> rows;
  std::vector<std::string> f;
  while (csv.next(f, 12)) {
    std::optional<double> v[12];
    for (std::size_t k = 0; k < 12; ++k) {
      if (k == 6 || k == 8) continue;  // the integer columns
      v[k] = csvNumber(f[k]);
      if (!v[k]) csv.fail(csv.line(), "field " + std::to_string(k + 1) + " '" + f[k] + "' is not a number");
    }
    const auto collisions = app::parseInteger(f[6], 0, std::numeric_limits<long long>::max());
    const auto groups = app::parseInteger(f[8], 0, std::numeric_limits<int>::max());
    if (!collisions) csv.fail(csv.line(), "collisions '" + f[6] + "' is not a count");
    if (!groups) csv.fail(csv.line(), "groups '" + f[8] + "' is not a count");
    monitor::TimeSeriesRow row;
    row.t_s = *v[0];
    row.d_nb_m = *v[1];
    row.centroid_x_m = *v[2];
    row.centroid_y_m = *v[3];
    row.drift_mps = *v[4];
    row.min_sep_m = *v[5];
    row.collisions = static_cast<std::uint64_t>(*collisions);
    row.spread_m = *v[7];
    row.groups = static_cast<int>(*groups);
    row.formation_error_m = *v[9];
    row.nees_pos = *v[10];
    row.nees_vel = *v[11];
    rows.push_back(row);
  }
  return rows;
}

std::vector<monitor::UavTrajectory> parseTrajectoriesCsv(std::istream& in, const std::string& source) {
  CsvReader csv(in, source, trajectoriesHeader());
  std::map<int, monitor::UavTrajectory> by_uav;
  std::vector<std::string> f;
  while (csv.next(f, 4)) {
    const auto t = csvNumber(f[0]);
    const auto uav = app::parseInteger(f[1], 0, std::numeric_limits<int>::max());
    const auto x = csvNumber(f[2]);
    const auto y = csvNumber(f[3]);
    if (!t || !std::isfinite(*t)) csv.fail(csv.line(), "t_s '" + f[0] + "' is not a time");
    if (!uav) csv.fail(csv.line(), "uav '" + f[1] + "' is not a UAV id");
    if (!x || !y) csv.fail(csv.line(), "x_m / y_m are not numbers");
    monitor::UavTrajectory& traj = by_uav[static_cast<int>(*uav)];
    traj.id = static_cast<int>(*uav);
    traj.points.push_back({*t, *x, *y});
  }
  std::vector<monitor::UavTrajectory> out;
  for (auto& [id, traj] : by_uav) out.push_back(std::move(traj));
  return out;
}

std::vector<sim::EventRecord> parseEventsCsv(std::istream& in, const std::string& source) {
  CsvReader csv(in, source, eventsHeader());
  std::vector<sim::EventRecord> events;
  std::vector<std::string> f;
  while (csv.next(f, 6)) {
    const auto t = csvNumber(f[0]);
    const auto uav = app::parseInteger(f[2], std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
    const auto other = app::parseInteger(f[3], std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
    const auto value = csvNumber(f[4]);
    if (!t || !std::isfinite(*t)) csv.fail(csv.line(), "t_s '" + f[0] + "' is not a time");
    if (f[1].empty()) csv.fail(csv.line(), "empty kind");
    if (!uav || !other) csv.fail(csv.line(), "uav / other_uav are not integers");
    if (!value) csv.fail(csv.line(), "value '" + f[4] + "' is not a number");
    events.push_back({*t, f[1], static_cast<int>(*uav), static_cast<int>(*other), *value, f[5]});
  }
  return events;
}

Json readJsonFile(const std::string& path) {
  const std::string text = readAll(path);
  try {
    return Json::parse(text);
  } catch (const Json::parse_error& e) {
    // "[json.exception.parse_error.101] parse error at line 1, column 14: syntax error ..." -> "line 1, ..."
    const std::string what = e.what();
    const auto at = what.find(" at line ");
    throw RunFileError(path + ": " + (at == std::string::npos ? what : what.substr(at + 4)));
  }
}

LoadedRun readRunDir(const std::string& dir) {
  namespace fs = std::filesystem;
  const auto path = [&dir](const char* name) { return (fs::path(dir) / name).string(); };
  if (!fs::is_directory(dir)) throw RunFileError(dir + ": not a directory");

  LoadedRun loaded;
  const std::string summary_path = path(kSummaryFile);
  loaded.summary = readJsonFile(summary_path);
  loaded.run = runFromSummaryJson(loaded.summary, summary_path);

  const auto open = [](const std::string& p) {
    auto in = std::make_unique<std::ifstream>(p, std::ios::binary);
    if (!*in) throw RunFileError("cannot read " + p);
    return in;
  };
  const std::string series_path = path(kTimeSeriesFile);
  loaded.run.series = parseTimeSeriesCsv(*open(series_path), series_path);
  const std::string traj_path = path(kTrajectoriesFile);
  loaded.run.trajectories = parseTrajectoriesCsv(*open(traj_path), traj_path);
  const std::string events_path = path(kEventsFile);
  loaded.run.events = parseEventsCsv(*open(events_path), events_path);
  return loaded;
}

std::string recordedVerdict(const std::string& dir) {
  try {
    const Json summary = readJsonFile((std::filesystem::path(dir) / kSummaryFile).string());
    const auto verdict = summary.find("verdict");
    return summary.is_object() && verdict != summary.end() && verdict->is_string() ? verdict->get<std::string>() : "";
  } catch (const RunFileError&) {
    return "";
  }
}

std::vector<std::string> recordedVerdictReasons(const std::string& dir) {
  std::vector<std::string> reasons;
  try {
    const Json summary = readJsonFile((std::filesystem::path(dir) / kSummaryFile).string());
    const auto list = summary.is_object() ? summary.find("verdict_reasons") : summary.end();
    if (list == summary.end() || !list->is_array()) return reasons;
    for (const Json& r : *list) {
      if (r.is_string()) reasons.push_back(r.get<std::string>());
    }
  } catch (const RunFileError&) {
  }
  return reasons;
}

}  // namespace swa::record
