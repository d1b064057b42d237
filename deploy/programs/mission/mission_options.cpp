#include "mission_options.h"

#include <sstream>

#include "swa/app/cli.h"
#include "swa/app/number.h"
#include "swa/dds/deployment.h"
#include "swa/dds/options.h"

namespace swa::mission_tool {
namespace {

app::Cli makeCli(MissionOptions& o) {
  app::Cli cli("swa_mission", "send a swarm mission from the ground to every agent of a running swarm.");
  cli.usage(
      "swa_mission (--leg vel:E,N,SECONDS | --leg to:E,N,SPEED)... [--expect N] [--stay] [--domain D]\n"
      "       swa_mission --hold [--expect N] [--domain D]");
  cli.details(R"(Writes swa/swarm/mission (SwarmMission) as the participant swa_ground: every agent and the monitor read
it, and each agent flies it from its next IMU sample, from the point its plan has reached (started there if none ran):
  vel:E,N,SECONDS  fly east E, north N m/s for SECONDS, then hold (a plain group velocity: it ends by itself, so a
                   ground link lost mid-command never sends the swarm away)
  to:E,N,SPEED     fly to the point E m east, N m north of where the swarm's mission began (the frame the UAVs had
                   then) at SPEED m/s
  --hold           stop where the plan has got to and hold there
Legs follow each other in the order given. A mission above --max-speed or otherwise unflyable is refused here and
nothing is sent; the agents check it again against their own mission.max_speed_mps and limits.
One writer: an agent flies the missions of the first swa_mission it hears until that one's participant leaves (it
exits, or its DDS lease expires); another writer's meanwhile are refused and counted in the agent's log.
Example: swa_mission --leg vel:0,2,30 --leg to:0,0,4    north at 2 m/s for 30 s, then back to the start at 4 m/s)");
  cli.list("--leg", "LEG", o.legs, "one leg: vel:E,N,SECONDS or to:E,N,SPEED (repeatable, flown in order)");
  cli.flag("--hold", o.hold, "stop and hold where the plan has got to");
  cli.real("--max-speed", "M/S", o.max_speed_mps, 0.01, 100.0, "a speed",
           "refuse legs faster than this (the agents' mission.max_speed_mps)");
  cli.integer("--expect", "N", o.expect, 0, 100000, "a count",
              "send once at least N readers (the agents, the monitor) have matched");
  cli.real("--wait-s", "SECONDS", o.wait_s, 0.0, 3600.0, "a time",
           "how long to wait for the readers, then again for their acknowledgment");
  cli.flag("--stay", o.stay,
           "keep the writer until SIGINT or SIGTERM (a ground station): an agent that joins later gets the mission");
  cli.domain(o.domain, dds::kMaxDomainId);
  cli.footer(R"(Exit status: 0 sent and acknowledged by every matched reader; 1 DDS failure (also: security credentials
             refused); 2 bad arguments or an unflyable mission (nothing sent); 3 fewer than --expect readers
             matched within --wait-s (nothing sent); 4 sent, but not every reader acknowledged it within --wait-s.

)" + dds::environmentHelp());
  return cli;
}

}  // namespace

std::optional<agent::MissionCommandLeg> parseLeg(const std::string& text, std::string& problem) {
  const auto colon = text.find(':');
  const std::string kind = colon == std::string::npos ? std::string() : text.substr(0, colon);
  agent::MissionCommandLeg leg;
  if (kind == "vel") {
    leg.kind = agent::MissionCommandLeg::Kind::kVelocity;
  } else if (kind == "to") {
    leg.kind = agent::MissionCommandLeg::Kind::kTo;
  } else {
    problem = "--leg '" + text + "' must be vel:E,N,SECONDS or to:E,N,SPEED";
    return std::nullopt;
  }
  std::vector<double> numbers;
  std::istringstream in(text.substr(colon + 1));
  for (std::string part; std::getline(in, part, ',');) {
    const std::optional<double> v = app::parseReal(part, -1e12, 1e12);
    if (!v) {
      problem = "--leg '" + text + "': '" + part + "' is not a number";
      return std::nullopt;
    }
    numbers.push_back(*v);
  }
  if (numbers.size() != 3) {
    problem = "--leg '" + text + "' needs three numbers: " + (kind == "vel" ? "E,N,SECONDS" : "E,N,SPEED");
    return std::nullopt;
  }
  leg.value = agent::Vec2(numbers[0], numbers[1]);
  (kind == "vel" ? leg.duration_s : leg.speed_mps) = numbers[2];
  return leg;
}

MissionOptions parseMissionOptions(const std::vector<std::string>& args) {
  return app::parseOptions<MissionOptions>(args, makeCli, [](MissionOptions& o, const app::Cli&, app::Problems& p) {
    if (o.hold && !o.legs.empty()) p.push_back("--hold and --leg: a hold has no legs");
    if (!o.hold && o.legs.empty()) p.push_back("nothing to send: give --leg (one or more) or --hold");
    o.command.hold = o.hold;
    for (const std::string& text : o.legs) {
      std::string problem;
      if (const auto leg = parseLeg(text, problem)) {
        o.command.legs.push_back(*leg);
      } else {
        p.push_back(problem);
      }
    }
    if (!p.empty()) return;
    // Points are checked against no position limit here (the agents' limits.max_abs_position_m decides).
    if (const auto why = agent::missionCommandProblem(o.command, o.max_speed_mps, 1e300)) {
      p.push_back("the mission cannot be flown: " + *why);
    }
  });
}

std::string missionUsage() { return app::helpText(makeCli); }

}  // namespace swa::mission_tool
