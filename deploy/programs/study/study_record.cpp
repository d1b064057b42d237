#include "study_record.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>

#include "study_html.h"
#include "swa/app/version.h"
#include "swa/run_record/csv.h"

namespace swa::study {
namespace {

namespace fs = std::filesystem;
using record::Json;

constexpr const char* kStudyFile = "study.json";
constexpr const char* kRunsFile = "runs.csv";
constexpr int kFormat = 1;  // of study.json

Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

std::uint64_t fnv1a(const std::string& text, std::uint64_t h = 1469598103934665603ull) {
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  return h;
}

Json planJson(const StudyPlan& plan) {
  Json axes = Json::array();
  for (const Axis& a : plan.axes) axes.push_back({{"key", a.key}, {"values", a.values}});
  Json j = {{"axes", axes}, {"seeds", plan.seeds}};
  // Only when there are some: a study without variants keeps the id and the files it had before they existed.
  if (!plan.variants.empty()) {
    Json variants = Json::array();
    for (const Variant& v : plan.variants) variants.push_back({{"name", v.name}, {"overrides", v.overrides}});
    j["variants"] = variants;
  }
  return j;
}

template <class T>
T field(const Json& j, const char* key, const std::string& source) {
  const auto it = j.find(key);
  if (it == j.end()) throw StudyError(source + ": no \"" + key + "\"");
  try {
    return it->get<T>();
  } catch (const std::exception&) {
    throw StudyError(source + ": \"" + key + "\" is not what a study.json holds there");
  }
}

std::string shardText(const Shard& s) { return std::to_string(s.index) + "/" + std::to_string(s.count); }

}  // namespace

std::string programVersion() { return app::programVersion(); }

std::string studyId(const std::string& version, const std::string& scenario_yaml, const StudyPlan& plan,
                    std::uint64_t first_seed) {
  std::uint64_t h = fnv1a(version);
  h = fnv1a(scenario_yaml, h);
  h = fnv1a(planJson(plan).dump(), h);
  h = fnv1a(std::to_string(first_seed), h);
  char id[17];
  std::snprintf(id, sizeof id, "%016llx", static_cast<unsigned long long>(h));
  return id;
}

Json studyJson(const StudyRecord& s) {
  Json runs = Json::array();
  for (const RunRow& r : s.runs) {
    Json metrics = Json::object();
    for (const monitor::NamedValue& m : r.metrics) metrics[m.key] = number(m.value);
    runs.push_back({{"index", r.index}, {"point", r.point}, {"seed", r.seed}, {"metrics", metrics}});
  }
  return {{"format", kFormat},           {"study_id", s.study_id},           {"version", s.version},
          {"scenario", s.scenario},      {"first_seed", s.first_seed},       {"plan", planJson(s.plan)},
          {"shard", shardText(s.shard)}, {"scenario_yaml", s.scenario_yaml}, {"runs", runs}};
}

StudyRecord studyFromJson(const Json& j, const std::string& source) {
  if (!j.is_object()) throw StudyError(source + ": not a study.json");
  if (field<int>(j, "format", source) != kFormat) throw StudyError(source + ": a study.json of another format");
  StudyRecord s;
  s.study_id = field<std::string>(j, "study_id", source);
  s.version = field<std::string>(j, "version", source);
  s.scenario = field<std::string>(j, "scenario", source);
  s.scenario_yaml = field<std::string>(j, "scenario_yaml", source);
  s.first_seed = field<std::uint64_t>(j, "first_seed", source);
  const Json plan = field<Json>(j, "plan", source);
  s.plan.seeds = field<int>(plan, "seeds", source);
  const Json axes = field<Json>(plan, "axes", source);
  if (plan.contains("variants")) {
    for (const Json& v : field<Json>(plan, "variants", source)) {
      s.plan.variants.push_back(
          {field<std::string>(v, "name", source), field<std::vector<std::string>>(v, "overrides", source)});
    }
  }
  for (const Json& a : axes) {
    s.plan.axes.push_back({field<std::string>(a, "key", source), field<std::vector<std::string>>(a, "values", source)});
  }
  try {
    s.shard = parseShard(field<std::string>(j, "shard", source));
  } catch (const std::invalid_argument&) {
    throw StudyError(source + ": a malformed shard");
  }
  const Json runs = field<Json>(j, "runs", source);
  for (const Json& r : runs) {
    RunRow row;
    row.index = field<std::size_t>(r, "index", source);
    row.point = field<std::size_t>(r, "point", source);
    row.seed = field<std::uint64_t>(r, "seed", source);
    const Json metrics = field<Json>(r, "metrics", source);
    for (const auto& [key, value] : metrics.items()) {
      row.metrics.push_back({key, value.is_number() ? value.get<double>() : monitor::kNaN});
    }
    s.runs.push_back(std::move(row));
  }
  return s;
}

StudyRecord mergeShards(const std::vector<StudyRecord>& shards) {
  if (shards.empty()) throw StudyError("nothing to merge");
  const StudyRecord& first = shards.front();
  StudyRecord merged = first;
  merged.shard = Shard{};
  merged.runs.clear();
  std::map<std::size_t, const RunRow*> by_index;
  for (std::size_t k = 0; k < shards.size(); ++k) {
    const StudyRecord& s = shards[k];
    const std::string which = "shard " + shardText(s.shard) + " (argument " + std::to_string(k + 1) + ")";
    if (s.version != first.version) {
      throw StudyError(which + " was run by " + s.version + ", the first by " + first.version + ": not mergeable");
    }
    if (s.study_id != first.study_id) {
      throw StudyError(which + " is of study " + s.study_id + ", the first of " + first.study_id +
                       " (another scenario, sweep, seeds or version)");
    }
    if (s.shard.count != first.shard.count) {
      throw StudyError(which + " is one of " + std::to_string(s.shard.count) + " shards, the first one of " +
                       std::to_string(first.shard.count) + ": merge the shards of one cut");
    }
    for (const RunRow& r : s.runs) {
      if (!by_index.emplace(r.index, &r).second) {
        throw StudyError(which + " repeats run " + std::to_string(r.index) + ": a shard given twice?");
      }
    }
  }
  const std::size_t total = runCount(first.plan);
  std::set<int> missing_shards;
  for (std::size_t i = 0; i < total; ++i) {
    if (by_index.count(i) == 0)
      missing_shards.insert(static_cast<int>(i % static_cast<std::size_t>(first.shard.count)) + 1);
  }
  if (!missing_shards.empty() || by_index.size() != total) {
    std::string list;
    for (const int s : missing_shards) list += " " + std::to_string(s) + "/" + std::to_string(first.shard.count);
    throw StudyError("runs are missing: shard(s)" + list + " not given (or incomplete)");
  }
  for (const auto& [index, row] : by_index) merged.runs.push_back(*row);
  return merged;
}

std::string tidyCsv(const StudyRecord& s) {
  std::string out;
  std::vector<std::string> header;
  std::set<std::string> swept;
  for (const Axis& a : s.plan.axes) {
    header.push_back(a.key);
    swept.insert(a.key);
  }
  header.push_back("seed");
  // A metric named like a swept key (uav_count, duration_s) repeats the swept value: one column, the swept one.
  const std::vector<monitor::NamedValue> keys =
      s.runs.empty() ? std::vector<monitor::NamedValue>{} : s.runs.front().metrics;
  for (const monitor::NamedValue& m : keys) {
    if (swept.count(m.key) == 0) header.push_back(m.key);
  }
  for (std::size_t k = 0; k < header.size(); ++k) out += (k ? "," : "") + record::csvField(header[k]);
  out += "\n";
  for (const RunRow& r : s.runs) {
    std::string line;
    for (const std::string& v : pointValues(s.plan, r.point)) line += record::csvField(v) + ",";
    line += std::to_string(r.seed);
    for (const monitor::NamedValue& m : r.metrics) {
      if (swept.count(m.key) == 0) line += "," + monitor::formatNumber(m.value);
    }
    out += line + "\n";
  }
  return out;
}

Json pointSummaryJson(const StudyRecord& s, std::size_t point) {
  std::vector<monitor::Summary> summaries;
  Json seeds = Json::array();
  for (const RunRow& r : s.runs) {
    if (r.point != point) continue;
    summaries.push_back(monitor::summaryFromFields(r.metrics));
    seeds.push_back(r.seed);
  }
  Json values = Json::object();
  const std::vector<std::string> v = pointValues(s.plan, point);
  for (std::size_t k = 0; k < v.size(); ++k) values[s.plan.axes[k].key] = v[k];
  return {{"study_id", s.study_id},
          {"point", point},
          {"values", values},
          {"seeds", seeds},
          {"aggregate", record::aggregateJson(monitor::aggregate(summaries))}};
}

void writeShard(const std::string& dir, const StudyRecord& shard) {
  fs::create_directories(dir);
  record::writeTextFile((fs::path(dir) / kStudyFile).string(), record::jsonText(studyJson(shard)));
}

void writeStudy(const std::string& dir, const StudyRecord& study) {
  writeShard(dir, study);
  record::writeTextFile((fs::path(dir) / kRunsFile).string(), tidyCsv(study));
  record::writeTextFile((fs::path(dir) / "study.html").string(), studyHtml(study));
  for (std::size_t p = 0; p < pointCount(study.plan); ++p) {
    const fs::path point_dir = fs::path(dir) / "points" / std::to_string(p);
    fs::create_directories(point_dir);
    record::writeTextFile((point_dir / record::kSummaryFile).string(), record::jsonText(pointSummaryJson(study, p)));
  }
}

StudyRecord readStudy(const std::string& dir) {
  const std::string path = (fs::path(dir) / kStudyFile).string();
  if (!fs::exists(path)) throw StudyError(dir + " has no " + kStudyFile + ": not a study or shard directory");
  try {
    return studyFromJson(record::readJsonFile(path), path);
  } catch (const StudyError&) {
    throw;
  } catch (const std::exception& e) {
    throw StudyError(path + ": " + e.what());
  }
}

void refuseOldStudy(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const char* entry : {"study.json", "points"}) {
    if (fs::exists(fs::path(dir) / entry, ec)) {
      throw StudyError(dir + " already holds a study (" + entry +
                       "): give a fresh --out, or remove the old study first");
    }
  }
}

}  // namespace swa::study
