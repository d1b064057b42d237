#pragma once
// A run directory's files (run_record.h): writing them at the end of a live run, and reading them back for
// --combine. The readers accept exactly what the writers produce (and CRLF line ends); anything else is a
// RunFileError naming the file and the line.

#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

#include "json_value.h"
#include "run_record.h"

namespace swa::monitor_node {

class RunFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline const char* kSummaryFile = "summary.json";
inline const char* kTimeSeriesFile = "timeseries.csv";
inline const char* kTrajectoriesFile = "trajectories.csv";
inline const char* kEventsFile = "events.csv";

inline const char* trajectoriesHeader() { return "t_s,uav,x_m,y_m"; }
inline const char* eventsHeader() { return "t_s,kind,uav,other_uav,value,text"; }

// summary.json of one run.
JsonValue summaryJson(const RunRecord& run);

std::string timeSeriesCsv(const std::vector<monitor::TimeSeriesRow>& series);
std::string trajectoriesCsv(const std::vector<monitor::UavTrajectory>& trajectories);
std::string eventsCsv(const std::vector<EventRecord>& events);

// Creates `dir` if needed and writes the four files. Throws RunFileError naming the file that failed.
void writeRunFiles(const std::string& dir, const RunRecord& run);

// Readers; `source` names the input in error messages.
RunRecord runFromSummaryJson(const JsonValue& summary, const std::string& source);
std::vector<monitor::TimeSeriesRow> parseTimeSeriesCsv(std::istream& in, const std::string& source);
std::vector<monitor::UavTrajectory> parseTrajectoriesCsv(std::istream& in, const std::string& source);
std::vector<EventRecord> parseEventsCsv(std::istream& in, const std::string& source);

struct LoadedRun {
  RunRecord run;
  JsonValue summary;  // summary.json as read (re-emitted in the combined summary)
};

// Reads the four files of `dir`. Throws RunFileError naming the file (missing, unreadable or malformed).
LoadedRun readRunDir(const std::string& dir);

}  // namespace swa::monitor_node
