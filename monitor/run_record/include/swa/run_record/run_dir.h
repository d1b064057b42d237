#pragma once
// A run directory: the files of one run (run_record.h), written by swa_monitor and swa_batch and read back by
// swa_monitor --combine, swa_launch and the tests.
//   summary.json      the RunRecord's fields, the summary keys as monitor::summaryFields (swa_batch's per-seed keys)
//   timeseries.csv    monitor::csvHeader() rows
//   trajectories.csv  t_s,uav,x_m,y_m (nan,nan: a gap in that UAV's line)
//   events.csv        t_s,kind,uav,other_uav,value,text
//   scenario.yaml     the effective scenario (written by whoever starts the run)
//   logs/restarts.csv the launcher's restart log (restarts.h)
// The readers accept exactly what the writers produce (and CRLF line ends); anything else is a RunFileError naming
// the file and the line. JSON goes through nlohmann::json, members in the order written.

#include <istream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "swa/run_record/run_record.h"

namespace swa::record {

using Json = nlohmann::ordered_json;

class RunFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline const char* kSummaryFile = "summary.json";
inline const char* kTimeSeriesFile = "timeseries.csv";
inline const char* kTrajectoriesFile = "trajectories.csv";
inline const char* kEventsFile = "events.csv";
inline const char* kScenarioFile = "scenario.yaml";

inline const char* trajectoriesHeader() { return "t_s,uav,x_m,y_m"; }
inline const char* eventsHeader() { return "t_s,kind,uav,other_uav,value,text"; }

Json summaryJson(const RunRecord& run);
// One member per monitor::summaryFields entry (swa_batch's per-seed entries), null where not finite.
Json metricsJson(const monitor::Summary& summary);
// {"runs": n, "metrics": {"<key>": {"runs": .., "mean": .., "std": .., "min": .., "max": ..}, ...}}
Json aggregateJson(const monitor::Aggregate& aggregate);
std::string timeSeriesCsv(const std::vector<monitor::TimeSeriesRow>& series);
std::string trajectoriesCsv(const std::vector<monitor::UavTrajectory>& trajectories);
std::string eventsCsv(const std::vector<sim::EventRecord>& events);

// Creates `dir` if needed and writes summary.json and the three CSV files. Throws RunFileError naming what failed.
void writeRunFiles(const std::string& dir, const RunRecord& run);
// One file, created or replaced; RunFileError naming it when it cannot be written.
void writeTextFile(const std::string& path, const std::string& content);
// Two-space indented JSON ending in a newline (NaN and infinities as null: JSON has no such numbers).
std::string jsonText(const Json& json);

// Readers; `source` names the input in error messages.
RunRecord runFromSummaryJson(const Json& summary, const std::string& source);
std::vector<monitor::TimeSeriesRow> parseTimeSeriesCsv(std::istream& in, const std::string& source);
std::vector<monitor::UavTrajectory> parseTrajectoriesCsv(std::istream& in, const std::string& source);
std::vector<sim::EventRecord> parseEventsCsv(std::istream& in, const std::string& source);
// A JSON file; RunFileError "path: line L, column C: what" when it is not readable JSON.
Json readJsonFile(const std::string& path);

struct LoadedRun {
  RunRecord run;
  Json summary;  // summary.json as read (re-emitted in a combined summary)
};

// Reads the four files of `dir`. Throws RunFileError naming the file (missing, unreadable or malformed).
LoadedRun readRunDir(const std::string& dir);

// The verdict ("PASS", "FAIL", "INCOMPLETE") that dir/summary.json records, or "" when there is none.
std::string recordedVerdict(const std::string& dir);
// Why the run in `dir` did not pass (its summary.json's verdict_reasons), or nothing if it passed or has no summary.
std::vector<std::string> recordedVerdictReasons(const std::string& dir);

}  // namespace swa::record
