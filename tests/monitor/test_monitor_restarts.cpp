// The launcher's restart log as swa_monitor reads it: missing or empty means no restart, the header may be absent
// or repeated, CRLF and quoting are tolerated, and every malformed row is counted and described, never fatal.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "scratch.h"
#include "swa/run_record/restarts.h"

namespace swa::record {
namespace {

RestartLog parse(const std::string& text) {
  std::istringstream in(text);
  return parseRestartLog(in);
}

TEST(RestartLog, MissingFileIsNoRestart) {
  // WHEN the restart log file does not exist
  const RestartLog log = readRestartLog("/nonexistent/swa_monitor_restarts.csv");
  // THEN it is not found, and there was no restart and nothing malformed
  EXPECT_FALSE(log.found);
  EXPECT_TRUE(log.restarts.empty());
  EXPECT_EQ(log.malformed_rows, 0);
}

TEST(RestartLog, EmptyOrHeaderOnlyIsNoRestart) {
  // GIVEN an empty log, a blank line, or the header alone (with or without its newline)
  for (const std::string text : {"", "\n", "wall_s,uav,exit_status,restart_count,backoff_s\n",
                                 "wall_s,uav,exit_status,restart_count,backoff_s"}) {
    // WHEN it is parsed
    const RestartLog log = parse(text);
    // THEN it is found, with no restart and nothing malformed
    EXPECT_TRUE(log.found);
    EXPECT_TRUE(log.restarts.empty());
    EXPECT_EQ(log.malformed_rows, 0);
  }
}

TEST(RestartLog, RowsInOrder) {
  // WHEN a log of three restarts is parsed, its last line without its newline
  const RestartLog log = parse(
      "wall_s,uav,exit_status,restart_count,backoff_s\n"
      "12.5,3,-9,1,0.5\n"
      "20,3,SIGKILL,2,1\n"
      "31.25,0,134,1,0.5");  // the last line still being written has no newline, but is complete
  // THEN every row is read, in order, with every field
  ASSERT_EQ(log.restarts.size(), 3u);
  EXPECT_EQ(log.malformed_rows, 0);
  EXPECT_DOUBLE_EQ(log.restarts[0].wall_s, 12.5);
  EXPECT_EQ(log.restarts[0].uav, 3);
  EXPECT_EQ(log.restarts[0].exit_status, "-9");
  EXPECT_EQ(log.restarts[0].restart_count, 1);
  EXPECT_DOUBLE_EQ(log.restarts[0].backoff_s, 0.5);
  EXPECT_EQ(log.restarts[1].exit_status, "SIGKILL");
  EXPECT_EQ(log.restarts[2].uav, 0);
  EXPECT_DOUBLE_EQ(log.restarts[2].wall_s, 31.25);
}

TEST(RestartLog, AMonitorRestartIsARowOfItsOwn) {
  // WHEN a log with an agent's restart, the monitor's, and a row naming "Monitor" is parsed
  const RestartLog log = parse(
      "wall_s,uav,exit_status,restart_count,backoff_s\n"
      "12.5,3,137,1,0.5\n"
      "20.0,monitor,137,1,0.5\n"
      "21.0,Monitor,137,1,0.5\n");
  // THEN the monitor's restart is a row of its own, and the misspelt one is malformed
  ASSERT_EQ(log.restarts.size(), 2u);
  EXPECT_EQ(log.restarts[0].uav, 3);
  EXPECT_EQ(log.restarts[1].uav, AgentRestart::kMonitor);
  EXPECT_EQ(log.malformed_rows, 1);  // the spelling is exact
}

TEST(RestartLog, ABridgeRestartNamesItsUav) {
  // WHEN a log with a bridge's restart, and rows naming a bridge without an index or with a bad one, is parsed
  const RestartLog log = parse(
      "wall_s,uav,exit_status,restart_count,backoff_s\n"
      "12.5,bridge_2,137,1,0.5\n"
      "13.0,bridge_,137,1,0.5\n"
      "14.0,bridge_x,137,1,0.5\n"
      "15.0,2,137,1,0.5\n");
  // THEN the bridge's restart is told from its agent's by the flag, and the others are malformed
  ASSERT_EQ(log.restarts.size(), 2u);
  EXPECT_EQ(log.restarts[0].uav, 2);
  EXPECT_TRUE(log.restarts[0].bridge);
  EXPECT_EQ(restartSubject(log.restarts[0]), "bridge_2");
  EXPECT_FALSE(log.restarts[1].bridge);
  EXPECT_EQ(restartSubject(log.restarts[1]), "2");
  EXPECT_EQ(log.malformed_rows, 2);
}

TEST(RestartLog, HeaderOptionalRepeatedCrLfSpacesAndQuotes) {
  // WHEN a log is parsed with a row before the header, CRLF line ends, spaces around fields, a quoted comma and a
  // blank line
  const RestartLog log = parse(
      "1,0,1,1,0.5\r\n"
      "wall_s,uav,exit_status,restart_count,backoff_s\r\n"
      " 2 , 1 ,\"killed, signal 9\", 1 , 1 \r\n"
      "\r\n");
  // THEN both rows are read, nothing is malformed, and the quoted field keeps its comma
  ASSERT_EQ(log.restarts.size(), 2u);
  EXPECT_EQ(log.malformed_rows, 0);
  EXPECT_EQ(log.restarts[1].uav, 1);
  EXPECT_EQ(log.restarts[1].exit_status, "killed, signal 9");
}

TEST(RestartLog, MalformedRowsAreCountedWithLineAndReason) {
  // WHEN a log with two good rows and one malformed row of each kind is parsed
  const RestartLog log = parse(
      "wall_s,uav,exit_status,restart_count,backoff_s\n"
      "1,0,1,1,0.5\n"
      "1,0,1,1\n"         // 4 fields
      "x,0,1,1,0.5\n"     // wall_s
      "1,-2,1,1,0.5\n"    // uav
      "1,0,,1,0.5\n"      // exit_status
      "1,0,1,-1,0.5\n"    // restart_count
      "1,0,1,1,nan\n"     // backoff_s
      "1,0,\"open,1,1\n"  // quotes
      "2,1,0,1,0.5\n");
  // THEN the good rows are read, and each malformed one is counted and described with its line
  EXPECT_EQ(log.restarts.size(), 2u);
  EXPECT_EQ(log.malformed_rows, 7);
  ASSERT_EQ(log.problems.size(), 7u);
  EXPECT_EQ(log.problems[0], "line 3: 4 fields, expected 5");
  EXPECT_NE(log.problems[1].find("line 4: wall_s 'x'"), std::string::npos);
  EXPECT_NE(log.problems[2].find("line 5: uav '-2'"), std::string::npos);
  EXPECT_NE(log.problems[3].find("line 6: exit_status is empty"), std::string::npos);
  EXPECT_NE(log.problems[4].find("line 7: restart_count '-1'"), std::string::npos);
  EXPECT_NE(log.problems[5].find("line 8: backoff_s 'nan'"), std::string::npos);
  EXPECT_EQ(log.problems[6], "line 9: unbalanced quotes");
}

TEST(RestartLog, ProblemListIsBoundedButTheCountIsNot) {
  // GIVEN a log of 50 garbage lines
  std::string text;
  for (int k = 0; k < 50; ++k) text += "garbage\n";
  // WHEN it is parsed THEN all 50 are counted as malformed, but only kMaxProblems of them are described
  const RestartLog log = parse(text);
  EXPECT_EQ(log.malformed_rows, 50);
  EXPECT_EQ(log.problems.size(), RestartLog::kMaxProblems);
}

TEST(RestartLog, ReadsAFile) {
  // GIVEN a restart log file with one restart of UAV 2
  const swa::testing::ScratchFile file(std::string(restartLogHeader()) + "\n5,2,1,1,0.5\n", ".csv");
  // WHEN it is read
  const RestartLog log = readRestartLog(file.path());
  // THEN it is found, with that restart
  EXPECT_TRUE(log.found);
  ASSERT_EQ(log.restarts.size(), 1u);
  EXPECT_EQ(log.restarts[0].uav, 2);
}

}  // namespace
}  // namespace swa::record
