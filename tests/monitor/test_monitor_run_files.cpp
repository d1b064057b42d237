// A run directory's files: what the writers produce reads back to the same run (numbers bit for bit, NaN gaps,
// quoted event text), summary.json carries swa_batch's per-seed keys, and malformed files are refused with the
// file and line named. Also the CSV reader underneath (JSON is nlohmann::json's).

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "scratch.h"
#include "swa/run_record/csv.h"
#include "swa/run_record/run_dir.h"

namespace swa::record {
namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool sameDouble(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

using swa::testing::ScratchDir;

RunRecord sampleRun() {
  RunRecord r;
  r.label = "swa";
  r.mode = "swa";
  r.scenario = "deploy/scenarios/dropout_4.yaml";
  r.seed = 18446744073709551615ull;  // survives the round trip exactly, unlike a double
  r.completed = true;
  r.end_reason = "completed";
  r.verdict.outcome = Outcome::kFail;
  r.verdict.reasons = {"1 collision(s)", "final d_NB \"odd\" text"};
  r.scoring.formation.radius_m = 12.0;
  r.scoring.radius_tolerance = 0.05;
  r.scoring.window_start_s = 10.0;
  r.summary.steps = 301;
  r.summary.duration_s = 30.0;
  r.summary.mean_neighbor_distance_m = 0.1 + 0.2;  // not a short decimal
  r.summary.collisions = 1;
  r.summary.groups = 1;
  r.summary.anees_position = kNaN;
  r.summary.nees_samples = 1234;
  r.counts = {{"truth_samples", 301}, {"dropped_state_late", 2}, {"dropped_truth_duplicate", 0}};
  r.restarts.found = true;
  r.restarts.restarts = {{12.5, 3, "-9", 1, 0.5}};
  r.restarts.malformed_rows = 1;
  r.restarts.problems = {"line 3: 4 fields, expected 5"};
  r.events = {{10.0, "gnss_lost", 0, -1, 0.0, "GNSS lost"},
              {12.34, "collision", 1, 2, 1.4999999999999998, "collision (value: distance, m)"},
              {13.0, "agent_dead", 3, -1, 2.0, "text with \"quotes\", commas\nand a line break"},
              {30.0, "scenario_end", sim::kAllUavs, -1, 0.0, "completed"}};
  for (int k = 0; k < 4; ++k) {
    monitor::TimeSeriesRow row;
    row.t_s = 0.1 * k;
    row.d_nb_m = 10.0 + 1.0 / 3.0 * k;
    row.centroid_x_m = -0.1 * k;
    row.collisions = static_cast<std::uint64_t>(k / 2);
    row.groups = 1 + k % 2;
    row.nees_pos = k == 0 ? kNaN : 2.0 / 3.0;
    r.series.push_back(row);
  }
  monitor::UavTrajectory a{0, {{0.0, 1.0, 2.0}, {0.5, kNaN, kNaN}, {1.0, 1.5, 2.5}}};
  monitor::UavTrajectory b{7, {{0.0, -1.0 / 3.0, 0.0}}};
  r.trajectories = {a, b};
  return r;
}

TEST(MonitorCsv, SplitsAndQuotes) {
  // WHEN lines are split THEN empty fields are kept and quoted fields lose their quotes, doubled quotes becoming one
  EXPECT_EQ(*splitCsvLine("a,b,,c"), (std::vector<std::string>{"a", "b", "", "c"}));
  EXPECT_EQ(*splitCsvLine(""), (std::vector<std::string>{""}));
  EXPECT_EQ(*splitCsvLine("\"x, y\",\"he said \"\"hi\"\"\""), (std::vector<std::string>{"x, y", "he said \"hi\""}));
  // AND a line with an unbalanced or misplaced quote does not split
  EXPECT_FALSE(splitCsvLine("\"open").has_value());
  EXPECT_FALSE(splitCsvLine("\"closed\"x,y").has_value());
  // WHEN fields are written THEN plain ones stay, ones with a comma, quote or edge space are quoted, a line break
  // becomes a space
  EXPECT_EQ(csvField("plain"), "plain");
  EXPECT_EQ(csvField("a,b"), "\"a,b\"");
  EXPECT_EQ(csvField("q\"q"), "\"q\"\"q\"");
  EXPECT_EQ(csvField("two\nlines"), "two lines");
  EXPECT_EQ(csvField(" padded"), "\" padded\"");
  // AND whatever is written splits back to itself
  for (const std::string s : {"a,b", "q\"q", " x ", "", "\"\""}) EXPECT_EQ(splitCsvLine(csvField(s))->at(0), s);
  // AND a trailing carriage return is chomped
  EXPECT_EQ(chompCr("x\r"), "x");
}

TEST(MonitorRunFiles, SummaryJsonHasTheBatchKeysAndTheMonitorsOwn) {
  // GIVEN a finished run's record
  const RunRecord run = sampleRun();
  // WHEN its summary.json object is made
  const Json j = summaryJson(run);
  // THEN it has every key of swa_batch's per-seed entries (metricsJson), with the same values
  const Json batch = metricsJson(run.summary);
  for (const auto& [key, value] : batch.items()) {
    ASSERT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j[key].dump(), value.dump()) << key;
  }
  // AND the monitor's own keys, with the verdict, the restart count, the events and the full 64-bit seed
  for (const char* key : {"label", "mode", "scenario", "seed", "completed", "end_reason", "verdict", "verdict_reasons",
                          "formation_radius_m", "tolerance", "agent_restarts", "restarts", "events",
                          "dropped_state_late", "truth_samples"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["verdict"].get<std::string>(), "FAIL");
  EXPECT_EQ(j["agent_restarts"].get<std::uint64_t>(), 1u);
  EXPECT_EQ(j["events"].size(), 4u);
  EXPECT_EQ(j["seed"].get<std::uint64_t>(), 18446744073709551615ull);
}

TEST(MonitorRunFiles, WhatIsWrittenReadsBack) {
  // GIVEN a run record with awkward values (NaN gaps, quotes and a line break in event text, a 64-bit seed)
  const ScratchDir dir("swa_monitor_roundtrip");
  const RunRecord in = sampleRun();
  // WHEN it is written to a run directory and read back
  writeRunFiles(dir.string(), in);
  const LoadedRun loaded = readRunDir(dir.string());
  const RunRecord& out = loaded.run;

  // THEN the run's description, verdict and summary are the same, numbers bit for bit
  EXPECT_EQ(out.label, in.label);
  EXPECT_EQ(out.mode, in.mode);
  EXPECT_EQ(out.scenario, in.scenario);
  EXPECT_EQ(out.seed, in.seed);
  EXPECT_EQ(out.completed, in.completed);
  EXPECT_EQ(out.end_reason, in.end_reason);
  EXPECT_EQ(out.verdict.outcome, in.verdict.outcome);
  EXPECT_EQ(out.verdict.reasons, in.verdict.reasons);
  EXPECT_EQ(out.scoring.formation.radius_m, in.scoring.formation.radius_m);
  EXPECT_EQ(out.scoring.radius_tolerance, in.scoring.radius_tolerance);
  EXPECT_EQ(out.scoring.window_start_s, in.scoring.window_start_s);
  const auto fin = monitor::summaryFields(in.summary);
  const auto fout = monitor::summaryFields(out.summary);
  ASSERT_EQ(fin.size(), fout.size());
  for (std::size_t k = 0; k < fin.size(); ++k) EXPECT_TRUE(sameDouble(fin[k].value, fout[k].value)) << fin[k].key;
  // AND of the counters only the dropped_* ones are read back (they are what the report shows), and the restart
  // log is the same
  EXPECT_EQ(out.counts, (std::vector<std::pair<std::string, std::uint64_t>>{{"dropped_state_late", 2},
                                                                            {"dropped_truth_duplicate", 0}}));
  ASSERT_EQ(out.restarts.restarts.size(), 1u);
  EXPECT_EQ(out.restarts.restarts[0].exit_status, "-9");
  EXPECT_EQ(out.restarts.restarts[0].uav, 3);
  EXPECT_EQ(out.restarts.malformed_rows, 1);
  EXPECT_EQ(out.restarts.problems, in.restarts.problems);

  // AND every event is the same, its text on one line
  ASSERT_EQ(out.events.size(), in.events.size());
  for (std::size_t k = 0; k < in.events.size(); ++k) {
    EXPECT_EQ(out.events[k].t_s, in.events[k].t_s);
    EXPECT_EQ(out.events[k].kind, in.events[k].kind);
    EXPECT_EQ(out.events[k].uav, in.events[k].uav);
    EXPECT_EQ(out.events[k].other_uav, in.events[k].other_uav);
    EXPECT_EQ(out.events[k].value, in.events[k].value);
  }
  EXPECT_EQ(out.events[2].text, "text with \"quotes\", commas and a line break");  // one record per line

  // AND the time series and the trajectories are the same, NaN gaps included
  ASSERT_EQ(out.series.size(), in.series.size());
  for (std::size_t k = 0; k < in.series.size(); ++k) {
    EXPECT_EQ(monitor::formatCsvRow(out.series[k]), monitor::formatCsvRow(in.series[k]));
  }
  ASSERT_EQ(out.trajectories.size(), 2u);
  for (std::size_t t = 0; t < 2; ++t) {
    EXPECT_EQ(out.trajectories[t].id, in.trajectories[t].id);
    ASSERT_EQ(out.trajectories[t].points.size(), in.trajectories[t].points.size());
    for (std::size_t p = 0; p < in.trajectories[t].points.size(); ++p) {
      EXPECT_TRUE(sameDouble(out.trajectories[t].points[p].x_m, in.trajectories[t].points[p].x_m));
      EXPECT_TRUE(sameDouble(out.trajectories[t].points[p].y_m, in.trajectories[t].points[p].y_m));
    }
  }
  // AND the summary object as read is the summary as written
  EXPECT_EQ(loaded.summary.dump(), summaryJson(in).dump());
}

TEST(MonitorRunFiles, CrLfFilesReadTheSame) {
  // WHEN a trajectories file with CRLF line ends and a blank last line is parsed
  std::istringstream in("t_s,uav,x_m,y_m\r\n0,1,2,3\r\n\r\n");
  const auto t = parseTrajectoriesCsv(in, "x.csv");
  // THEN it reads as with LF line ends
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].points.at(0).y_m, 3.0);
}

// The RunFileError message of reading `text` with `reader`, "" when it reads.
template <class Reader>
std::string errorOf(Reader reader, const std::string& text) {
  std::istringstream in(text);
  try {
    reader(in, "the.csv");
  } catch (const RunFileError& e) {
    return e.what();
  }
  return "";
}

TEST(MonitorRunFiles, MalformedCsvNamesFileAndLine) {
  // GIVEN the readers of the three CSV files
  const auto series = [](std::istream& in, const std::string& s) { return parseTimeSeriesCsv(in, s); };
  const auto traj = [](std::istream& in, const std::string& s) { return parseTrajectoriesCsv(in, s); };
  const auto events = [](std::istream& in, const std::string& s) { return parseEventsCsv(in, s); };
  const std::string h = monitor::csvHeader() + "\n";
  // WHEN a time series file is empty, has the wrong header, a row of the wrong length, a field that is no number, a
  // negative or fractional count THEN the error names the file and line and says what is wrong
  EXPECT_EQ(errorOf(series, ""), "the.csv:1: empty file, expected the header '" + monitor::csvHeader() + "'");
  EXPECT_NE(errorOf(series, "t,d\n").find("the.csv:1: header is not"), std::string::npos);
  EXPECT_NE(errorOf(series, h + "1,2,3\n").find("the.csv:2: 3 fields, expected 12"), std::string::npos);
  EXPECT_NE(errorOf(series, h + "0,x,0,0,0,0,0,0,1,0,0,0\n").find("the.csv:2: field 2 'x'"), std::string::npos);
  EXPECT_NE(errorOf(series, h + "0,1,0,0,0,0,-1,0,1,0,0,0\n").find("collisions '-1'"), std::string::npos);
  EXPECT_NE(errorOf(series, h + "0,1,0,0,0,0,0,0,1.5,0,0,0\n").find("groups '1.5'"), std::string::npos);
  // AND NaN where a value may be missing is no error
  EXPECT_EQ(errorOf(series, h + "0,nan,nan,nan,nan,nan,0,nan,0,nan,nan,nan\n"), "");
  // WHEN a trajectories row has a negative UAV or a NaN time THEN the error names them
  EXPECT_NE(errorOf(traj, "t_s,uav,x_m,y_m\n0,-1,0,0\n").find("the.csv:2: uav '-1'"), std::string::npos);
  EXPECT_NE(errorOf(traj, "t_s,uav,x_m,y_m\nnan,1,0,0\n").find("t_s 'nan'"), std::string::npos);
  // WHEN an events row has an empty kind, unbalanced quotes or ids that are no integers THEN the error says so
  EXPECT_NE(errorOf(events, "t_s,kind,uav,other_uav,value,text\n1,,0,0,0,x\n").find("empty kind"), std::string::npos);
  EXPECT_NE(errorOf(events, "t_s,kind,uav,other_uav,value,text\n1,k,0,0,0,\"x\n").find("unbalanced quotes"),
            std::string::npos);
  EXPECT_NE(errorOf(events, "t_s,kind,uav,other_uav,value,text\n1,k,a,0,0,x\n").find("not integers"),
            std::string::npos);
}

TEST(MonitorRunFiles, MissingOrBrokenFilesAreNamed) {
  // GIVEN an empty directory and a way to read it as a run directory
  const ScratchDir dir("swa_monitor_broken");
  const auto errorReading = [&dir] {
    try {
      readRunDir(dir.string());
    } catch (const RunFileError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  // THEN reading it names the missing summary.json
  EXPECT_NE(errorReading().find("cannot read " + (dir / "summary.json").string()), std::string::npos);
  // WHEN a run is written there and events.csv removed THEN reading names events.csv
  writeRunFiles(dir.string(), sampleRun());
  fs::remove(dir / "events.csv");
  EXPECT_NE(errorReading().find("cannot read " + (dir / "events.csv").string()), std::string::npos);
  // WHEN summary.json lacks the verdict, is cut short, or is not an object THEN reading names the file and the cause
  std::ofstream(dir / "summary.json") << "{\"label\": \"x\", \"completed\": true}";
  EXPECT_NE(errorReading().find("summary.json: no member 'verdict'"), std::string::npos);
  std::ofstream(dir / "summary.json") << "{\"label\": \"x\",";
  EXPECT_NE(errorReading().find("summary.json: line 1"), std::string::npos);
  std::ofstream(dir / "summary.json") << "[]";
  EXPECT_NE(errorReading().find("summary.json: not a JSON object"), std::string::npos);
  // WHEN the directory does not exist THEN reading says so
  try {
    readRunDir((dir / "nope").string());
    FAIL();
  } catch (const RunFileError& e) {
    EXPECT_NE(std::string(e.what()).find("not a directory"), std::string::npos);
  }
}

}  // namespace
}  // namespace swa::record
