#pragma once
// Command line of swa_replay (parsing apart from main() so it can be tested; every problem reported at once).

#include <optional>
#include <string>
#include <vector>

namespace swa::replay {

struct ReplayOptions {
  std::string file;                    // FILE.mcap, the first argument
  std::optional<int> uav;              // --uav I: only this UAV's inputs (and, with --check, commands)
  double speed = 1.0;                  // --speed X: recorded seconds per wall second; 0 = as fast as possible
  bool lockstep = false;               // --lockstep: wait for the agents' answer to each IMU sample
  bool check = false;                  // --check: in-process, no DDS
  std::string scenario_path;           // --scenario FILE: parameters instead of the recorded ones
  std::vector<std::string> overrides;  // --set key=value on top of them
  std::optional<std::string> domain;   // --domain D
  double wait_s = 30.0;                // --wait-s S: for the agents' readers before replaying
  bool help = false;
};

// Throws std::invalid_argument listing every problem, one per line.
ReplayOptions parseReplayOptions(const std::vector<std::string>& args);
std::string replayUsage();

// Exit status of swa_replay.
enum ExitCode : int {
  kExitOk = 0,         // replayed; --check: every command identical; --lockstep: every answer identical
  kExitDifferent = 1,  // --check or --lockstep: commands differ from the recorded ones (or are missing)
  kExitBadInput = 2,   // bad arguments, unreadable or malformed recording, bad parameters
};

}  // namespace swa::replay
