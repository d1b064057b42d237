#pragma once
// The launcher's restart log (--restarts FILE): CSV with the header
//   wall_s,uav,exit_status,restart_count,backoff_s
// and one row per agent restart (uav: its index), autopilot-bridge restart (uav: "bridge_<index>") or monitor restart
// (uav: "monitor"), appended while the run goes
// on and read by the monitor at the end. The file is someone else's, possibly still being written: a missing or
// empty file means no restart, and a malformed row is counted and described, never fatal.

#include <cstdint>
#include <istream>
#include <string>
#include <vector>

namespace swa::record {

struct AgentRestart {
  static constexpr int kMonitor = -1;  // `uav` of a restart of swa_monitor itself
  double wall_s = 0.0;                 // launcher's wall clock, seconds since it started
  int uav = 0;
  std::string exit_status;         // as the launcher wrote it (an exit code, or a signal name / number)
  std::int64_t restart_count = 0;  // restarts of that agent so far, this one included
  double backoff_s = 0.0;          // wait before the restart
  bool bridge = false;             // the UAV's swa_px4_bridge, not its agent
};

struct RestartLog {
  bool found = false;  // the file existed and could be opened
  std::vector<AgentRestart> restarts;
  int malformed_rows = 0;
  std::vector<std::string> problems;  // "line N: why", the first kMaxProblems of them
  static constexpr std::size_t kMaxProblems = 10;
};

inline const char* restartLogHeader() { return "wall_s,uav,exit_status,restart_count,backoff_s"; }
inline constexpr const char* kBridgePrefix = "bridge_";
// The uav column of a restart: "3", "bridge_3", "monitor".
std::string restartSubject(const AgentRestart& r);

// Blank lines and header lines (anywhere: a restarted launcher may write it again) are skipped. A row needs
// exactly five fields: wall_s and backoff_s finite reals >= 0, uav an integer in [0, 1000000], "bridge_" and such an
// integer, or "monitor", exit_status
// non-empty, restart_count an integer >= 0 (spaces around a field are ignored).
RestartLog parseRestartLog(std::istream& in);

// A missing file is an empty log with found = false.
RestartLog readRestartLog(const std::string& path);

}  // namespace swa::record
