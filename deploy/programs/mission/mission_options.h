#pragma once
// Command line of swa_mission, the ground's mission sender. Parsing is separate from main() so it can be tested; every
// problem is reported at once, and a mission that cannot be flown is refused here, before anything is sent.

#include <optional>
#include <string>
#include <vector>

#include "swa/agent/mission.h"

namespace swa::mission_tool {

struct MissionOptions {
  agent::MissionCommand command;      // --leg ..., or --hold
  std::vector<std::string> legs;      // --leg as written, in order
  bool hold = false;                  // --hold
  double max_speed_mps = 5.0;         // --max-speed: the agents' mission.max_speed_mps
  int expect = 1;                     // --expect N readers matched before sending
  double wait_s = 10.0;               // --wait-s: for the readers, then for their acknowledgment
  bool stay = false;                  // --stay: keep the writer until SIGINT / SIGTERM
  std::optional<std::string> domain;  // --domain D (else SWA_DOMAIN, else 0)
  bool help = false;
};

// One --leg: "vel:E,N,SECONDS" (a group velocity in m/s for a time) or "to:E,N,SPEED" (a point in m of the mission's
// frame at a speed in m/s); the problem in words if it is neither.
std::optional<agent::MissionCommandLeg> parseLeg(const std::string& text, std::string& problem);

// Accepts "--opt value" and "--opt=value". Throws std::invalid_argument listing every problem, one per line.
MissionOptions parseMissionOptions(const std::vector<std::string>& args);
std::string missionUsage();

}  // namespace swa::mission_tool
