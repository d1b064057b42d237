// swa_monitor --combine: run directories written by live monitors become one report and one summary, the exit
// status is the first run's verdict, and bad inputs give exit status 2 with the offending file named.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "combine.h"
#include "scratch.h"
#include "swa/run_record/run_dir.h"
#include "swa/run_record/run_report.h"

namespace swa::monitor_node {
namespace {

using record::Outcome;
using record::RunRecord;
using record::writeRunFiles;

namespace fs = std::filesystem;

class CombineTest : public ::testing::Test {
 protected:
  std::string writeRun(const std::string& name, Outcome outcome, double d_nb) {
    RunRecord r;
    r.label = name;
    r.mode = name;
    r.scenario = "deploy/scenarios/dropout_4.yaml";
    r.seed = 1;
    r.completed = outcome != Outcome::kIncomplete;
    r.end_reason = r.completed ? "completed" : "interrupted by SIGINT";
    r.verdict.outcome = outcome;
    if (outcome != Outcome::kPass) r.verdict.reasons = {"something <failed>"};
    r.scoring.window_start_s = 10.0;
    r.summary.steps = 3;
    r.summary.mean_neighbor_distance_m = d_nb;
    for (int k = 0; k < 3; ++k) {
      monitor::TimeSeriesRow row;
      row.t_s = 0.1 * k;
      row.d_nb_m = d_nb;
      r.series.push_back(row);
    }
    r.trajectories = {{0, {{0.0, 0.0, 0.0}, {0.2, 1.0, 0.0}}}, {1, {{0.0, 10.0, 0.0}, {0.2, 11.0, 0.0}}}};
    r.events = {{0.1, "agent_dead", 1, -1, 2.0, "no answer within the agent timeout"}};
    r.restarts.restarts = {{3.5, 1, "SIGKILL", 1, 0.5}};
    const std::string dir = (root_ / name).string();
    writeRunFiles(dir, r);
    return dir;
  }

  int combine(const std::vector<std::string>& args, std::string& out, std::string& err) {
    std::ostringstream o, e;
    const int status = runCombine(parseMonitorOptions(args), o, e);
    out = o.str();
    err = e.str();
    return status;
  }

  std::string read(const fs::path& p) {
    std::ifstream in(p);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }

  swa::testing::ScratchDir root_{"swa_monitor_combine"};
};

TEST_F(CombineTest, OneReportOneSummaryFirstRunsVerdict) {
  // GIVEN a passing SWA run and a failing standalone run, each in a run directory written by a live monitor
  const std::string a = writeRun("swa", Outcome::kPass, 9.9);
  const std::string b = writeRun("standalone", Outcome::kFail, 19.0);
  const std::string out_dir = (root_ / "combined").string();
  std::string out, err;
  // WHEN they are combined under the labels SWA and baseline
  // THEN the exit status is the first run's PASS (0) and the report's path is printed
  EXPECT_EQ(combine({"--combine", "SWA=" + a, "baseline=" + b, "--out", out_dir}, out, err), 0) << err;
  EXPECT_NE(out.find("report " + (fs::path(out_dir) / "report.html").string()), std::string::npos) << out;

  // AND summary.json holds both runs under their --combine labels, each with its whole summary
  const record::Json summary = record::Json::parse(read(fs::path(out_dir) / "summary.json"));
  ASSERT_TRUE(summary.contains("runs"));
  const record::Json& runs = summary["runs"];
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0]["label"].get<std::string>(), "SWA");  // the --combine label
  EXPECT_EQ(runs[1]["label"].get<std::string>(), "baseline");
  EXPECT_EQ(runs[1]["verdict"].get<std::string>(), "FAIL");
  EXPECT_DOUBLE_EQ(runs[1]["mean_neighbor_distance_m"].get<double>(), 19.0);
  EXPECT_EQ(runs[0]["events"].size(), 1u);  // each run's whole summary.json

  // AND report.html shows both runs' verdict reasons, events, restarts and trajectories, and the d_NB plot is beside it
  const std::string html = read(fs::path(out_dir) / "report.html");
  for (const char* must : {"SWA", "baseline", "something &lt;failed&gt;", "table-events", "agent_dead",
                           "table-restarts", "SIGKILL", "trajectories_SWA", "trajectories_baseline"}) {
    EXPECT_NE(html.find(must), std::string::npos) << must;
  }
  EXPECT_TRUE(fs::exists(fs::path(out_dir) / "d_nb.svg"));

  // WHEN the failing run comes first THEN the exit status is its FAIL (1), and an incomplete first run gives 3
  EXPECT_EQ(combine({"--combine", "b=" + b, "a=" + a, "--out", out_dir}, out, err), 1);
  const std::string c = writeRun("cut", Outcome::kIncomplete, 10.0);
  EXPECT_EQ(combine({"--combine", "c=" + c, "a=" + a, "--out", out_dir}, out, err), 3);
}

TEST_F(CombineTest, ScenarioGivesTheReportsReferenceValues) {
  // GIVEN a passing run and a scenario file with spacing 12 m and the GNSS loss at 20 s
  const std::string a = writeRun("swa", Outcome::kPass, 9.9);
  const fs::path scenario = root_ / "s.yaml";
  std::ofstream(scenario)
      << "uav_count: 4\nduration_s: 60\nformation:\n  spacing_m: 12.0\ngnss:\n  dropout_start_s: 20\n";
  const std::string out_dir = (root_ / "with_scenario").string();
  std::string out, err;
  // WHEN the run is combined with --scenario
  ASSERT_EQ(combine({"--combine", "x=" + a, "--out", out_dir, "--scenario", scenario.string()}, out, err), 0) << err;
  // THEN the report's reference lines come from the scenario
  const std::string html = read(fs::path(out_dir) / "report.html");
  EXPECT_NE(html.find("12 m"), std::string::npos);  // r from the scenario (spacing), not the run's 10 m
  EXPECT_NE(html.find("20 s"), std::string::npos);  // GNSS loss line
}

TEST_F(CombineTest, BadInputsAreExitTwoAndNamed) {
  // GIVEN a run directory
  const std::string a = writeRun("swa", Outcome::kPass, 9.9);
  const std::string out_dir = (root_ / "bad").string();
  std::string out, err;
  // WHEN a directory that does not exist is combined THEN exit status 2, naming it
  EXPECT_EQ(combine({"--combine", "x=" + (root_ / "missing").string(), "--out", out_dir}, out, err), 2);
  EXPECT_NE(err.find("missing: not a directory"), std::string::npos) << err;

  // WHEN a run directory lacks trajectories.csv THEN exit status 2, naming the file
  fs::remove(fs::path(a) / "trajectories.csv");
  EXPECT_EQ(combine({"--combine", "x=" + a, "--out", out_dir}, out, err), 2);
  EXPECT_NE(err.find("trajectories.csv"), std::string::npos) << err;

  // WHEN a run directory's timeseries.csv is garbage THEN exit status 2, naming the file and line
  const std::string b = writeRun("other", Outcome::kPass, 9.9);
  std::ofstream(fs::path(b) / "timeseries.csv") << "garbage\n";
  EXPECT_EQ(combine({"--combine", "x=" + b, "--out", out_dir}, out, err), 2);
  EXPECT_NE(err.find("timeseries.csv:1: header is not"), std::string::npos) << err;

  // WHEN the --scenario file does not exist THEN exit status 2, saying the scenario is invalid
  const std::string c = writeRun("third", Outcome::kPass, 9.9);
  EXPECT_EQ(combine({"--combine", "x=" + c, "--out", out_dir, "--scenario", (root_ / "nope.yaml").string()}, out, err),
            2);
  EXPECT_NE(err.find("invalid scenario"), std::string::npos) << err;
  // AND no report was written for any of these
  EXPECT_FALSE(fs::exists(fs::path(out_dir) / "report.html"));  // nothing written on bad input
}

}  // namespace
}  // namespace swa::monitor_node
