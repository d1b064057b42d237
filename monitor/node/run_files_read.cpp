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

#include "csv_text.h"
#include "run_files.h"

namespace swa::monitor_node {
namespace {

// A whole field as a double, "nan" / "inf" included (the writers' monitor::formatNumber output).
std::optional<double> number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || (errno == ERANGE && std::isinf(v))) return std::nullopt;
  return v;
}

std::optional<long long> integer(const std::string& text, long long min, long long max) {
  if (text.empty()) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (errno != 0 || end != text.c_str() + text.size() || v < min || v > max) return std::nullopt;
  return v;
}

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

double numberOrNaN(const JsonValue& j, const char* key) {
  const JsonValue* v = j.find(key);
  if (v == nullptr) return monitor::kNaN;
  return v->asNumber().value_or(monitor::kNaN);
}

}  // namespace

RunRecord runFromSummaryJson(const JsonValue& j, const std::string& source) {
  const auto fail = [&source](const std::string& what) { throw RunFileError(source + ": " + what); };
  if (!j.isObject()) fail("not a JSON object");
  RunRecord run;
  const JsonValue* label = j.find("label");
  const JsonValue* verdict = j.find("verdict");
  const JsonValue* completed = j.find("completed");
  if (label == nullptr || !label->asString()) fail("no string member 'label'");
  if (verdict == nullptr || !verdict->asString() || !parseOutcome(*verdict->asString())) {
    fail("no member 'verdict' with PASS, FAIL or INCOMPLETE");
  }
  if (completed == nullptr || !completed->asBool()) fail("no boolean member 'completed'");
  run.label = *label->asString();
  run.verdict.outcome = *parseOutcome(*verdict->asString());
  run.completed = *completed->asBool();
  if (const JsonValue* v = j.find("mode")) run.mode = v->asString().value_or("unknown");
  if (const JsonValue* v = j.find("scenario")) run.scenario = v->asString().value_or("");
  if (const JsonValue* v = j.find("seed")) run.seed = v->asUnsigned();
  if (const JsonValue* v = j.find("end_reason")) run.end_reason = v->asString().value_or("");
  if (const JsonValue* v = j.find("verdict_reasons")) {
    for (const JsonValue& r : v->items()) run.verdict.reasons.push_back(r.asString().value_or(""));
  }
  if (const double r = numberOrNaN(j, "formation_radius_m"); std::isfinite(r)) run.formation_radius_m = r;
  if (const double t = numberOrNaN(j, "tolerance"); std::isfinite(t)) run.tolerance = t;
  if (const double c = numberOrNaN(j, "collision_distance_m"); std::isfinite(c)) run.collision_distance_m = c;
  if (const double w = numberOrNaN(j, "window_from_s"); std::isfinite(w)) run.window_start_s = w;

  std::vector<monitor::NamedValue> fields;
  for (const monitor::NamedValue& f : monitor::summaryFields(monitor::Summary{})) {
    fields.push_back({f.key, numberOrNaN(j, f.key.c_str())});
  }
  run.summary = monitor::summaryFromFields(fields);

  run.restarts.found = true;
  if (const JsonValue* v = j.find("restarts_malformed_rows")) {
    run.restarts.malformed_rows = static_cast<int>(v->asInteger().value_or(0));
  }
  if (const JsonValue* v = j.find("restarts_problems")) {
    for (const JsonValue& p : v->items()) run.restarts.problems.push_back(p.asString().value_or(""));
  }
  if (const JsonValue* v = j.find("restarts")) {
    for (const JsonValue& r : v->items()) {
      AgentRestart a;
      a.wall_s = numberOrNaN(r, "wall_s");
      if (const JsonValue* x = r.find("uav")) a.uav = static_cast<int>(x->asInteger().value_or(-1));
      if (const JsonValue* x = r.find("exit_status")) a.exit_status = x->asString().value_or("");
      if (const JsonValue* x = r.find("restart_count")) a.restart_count = x->asInteger().value_or(0);
      a.backoff_s = numberOrNaN(r, "backoff_s");
      run.restarts.restarts.push_back(a);
    }
  }
  for (const auto& [key, value] : j.members()) {
    if (key.rfind("dropped_", 0) == 0) {
      if (const auto n = value.asUnsigned()) run.counts.emplace_back(key, *n);
    }
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
      v[k] = number(f[k]);
      if (!v[k]) csv.fail(csv.line(), "field " + std::to_string(k + 1) + " '" + f[k] + "' is not a number");
    }
    const auto collisions = integer(f[6], 0, std::numeric_limits<long long>::max());
    const auto groups = integer(f[8], 0, std::numeric_limits<int>::max());
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
    const auto t = number(f[0]);
    const auto uav = integer(f[1], 0, std::numeric_limits<int>::max());
    const auto x = number(f[2]);
    const auto y = number(f[3]);
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

std::vector<EventRecord> parseEventsCsv(std::istream& in, const std::string& source) {
  CsvReader csv(in, source, eventsHeader());
  std::vector<EventRecord> events;
  std::vector<std::string> f;
  while (csv.next(f, 6)) {
    const auto t = number(f[0]);
    const auto uav = integer(f[2], std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
    const auto other = integer(f[3], std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
    const auto value = number(f[4]);
    if (!t || !std::isfinite(*t)) csv.fail(csv.line(), "t_s '" + f[0] + "' is not a time");
    if (f[1].empty()) csv.fail(csv.line(), "empty kind");
    if (!uav || !other) csv.fail(csv.line(), "uav / other_uav are not integers");
    if (!value) csv.fail(csv.line(), "value '" + f[4] + "' is not a number");
    events.push_back({*t, f[1], static_cast<int>(*uav), static_cast<int>(*other), *value, f[5]});
  }
  return events;
}

LoadedRun readRunDir(const std::string& dir) {
  namespace fs = std::filesystem;
  const auto path = [&dir](const char* name) { return (fs::path(dir) / name).string(); };
  if (!fs::is_directory(dir)) throw RunFileError(dir + ": not a directory");

  LoadedRun loaded;
  const std::string summary_path = path(kSummaryFile);
  try {
    loaded.summary = JsonValue::parse(readAll(summary_path));
  } catch (const JsonError& e) {
    throw RunFileError(summary_path + ": " + e.what());
  }
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

}  // namespace swa::monitor_node
