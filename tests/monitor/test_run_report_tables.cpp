// The events and restarts tables of report.html (swa/run_record/run_report.h): one row per event or restart of every
// run, a "run" column only when there are several runs, and at most kMaxTableRows rows with the rest counted in the
// note.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "swa/run_record/run_report.h"

namespace swa::record {
namespace {

RunRecord runWith(const std::string& label, std::vector<sim::EventRecord> events,
                  std::vector<AgentRestart> restarts = {}, int malformed = 0) {
  RunRecord r;
  r.label = label;
  r.events = std::move(events);
  r.restarts.restarts = std::move(restarts);
  r.restarts.malformed_rows = malformed;
  return r;
}

sim::EventRecord collision(double t_s, int uav, int other, double separation_m) {
  return sim::EventRecord{t_s, sim::event_kind::kCollision, uav, other, separation_m, "too close"};
}

TEST(RunReportTables, OneRunListsEveryFieldOfAnEventInItsColumnAndNoRunColumn) {
  // GIVEN one run with a collision and a GNSS loss of every UAV
  const std::vector<RunRecord> runs{runWith(
      "swa",
      {collision(12.345, 2, 5, 0.75), sim::EventRecord{10.0, sim::event_kind::kGnssLost, sim::kAllUavs, -1, 0.0, ""}})};
  // WHEN its events table is made
  const monitor::ReportTable t = eventsTable(runs);
  // THEN it has the six columns and one row per event, blanks where there is no second UAV or value
  EXPECT_EQ(t.id, "events");
  EXPECT_EQ(t.columns, (std::vector<std::string>{"sim time [s]", "event", "UAV", "other UAV", "value", "detail"}));
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0], (std::vector<std::string>{"12.35", "collision", "2", "5", "0.75", "too close"}));
  EXPECT_EQ(t.rows[1], (std::vector<std::string>{"10", "gnss_lost", "all", "", "", ""}));
  EXPECT_EQ(t.note.find("Only the first"), std::string::npos) << t.note;
}

TEST(RunReportTables, SeveralRunsGetARunColumnAndTheTableStopsAtItsLimit) {
  // GIVEN two runs, the second with more events than a table lists
  std::vector<sim::EventRecord> many;
  for (std::size_t i = 0; i < kMaxTableRows + 10; ++i) many.push_back(collision(static_cast<double>(i), 0, 1, 0.5));
  const std::vector<RunRecord> runs{runWith("swa", {collision(1.0, 3, 4, 0.25)}), runWith("standalone", many)};
  // WHEN the events table is made
  const monitor::ReportTable t = eventsTable(runs);
  // THEN every row starts with its run's label, the table stops at its limit, and the note says how many there were
  EXPECT_EQ(t.columns.front(), "run");
  ASSERT_EQ(t.rows.size(), kMaxTableRows);
  EXPECT_EQ(t.rows[0].front(), "swa");
  EXPECT_EQ(t.rows[1].front(), "standalone");
  EXPECT_EQ(t.rows[1].size(), 7u);
  EXPECT_NE(t.note.find("Only the first 500 of 511 events are listed"), std::string::npos) << t.note;
}

TEST(RunReportTables, RestartsNameTheMonitorAndCountMalformedRows) {
  // GIVEN a run with an agent's restart, the monitor's, a bridge's, and two malformed rows in the restart log
  const std::vector<RunRecord> runs{
      runWith("swa", {},
              {AgentRestart{15.25, 1, "137", 1, 0.5}, AgentRestart{52.8, AgentRestart::kMonitor, "137", 1, 0.5},
               AgentRestart{60.0, 3, "137", 1, 0.5, /*bridge=*/true}},
              2)};
  // WHEN the restarts table is made
  const monitor::ReportTable t = restartsTable(runs);
  // THEN one row each, the monitor by name, and the malformed rows in the note
  EXPECT_EQ(t.columns,
            (std::vector<std::string>{"wall time [s]", "UAV", "exit status", "restart count", "backoff [s]"}));
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.rows[0], (std::vector<std::string>{"15.25", "1", "137", "1", "0.5"}));
  EXPECT_EQ(t.rows[1][1], "monitor");
  EXPECT_EQ(t.rows[2][1], "bridge_3");
  EXPECT_NE(t.note.find("2 malformed row(s) skipped"), std::string::npos) << t.note;
  // AND a run without any has an empty table with its own text
  EXPECT_TRUE(restartsTable({runWith("swa", {})}).rows.empty());
  EXPECT_EQ(restartsTable({runWith("swa", {})}).empty_text, "No restart.");
}

}  // namespace
}  // namespace swa::record
