#include "swa/wire/mission.h"

namespace swa::wire {

msg::SwarmMission toMsg(const agent::MissionCommand& command, std::int64_t stamp_ns, std::uint32_t seq) {
  msg::SwarmMission m;
  m.header().stamp_ns(stamp_ns);
  m.header().seq(seq);
  m.command(command.hold ? msg::MISSION_HOLD : msg::MISSION_LEGS);
  m.legs().reserve(command.legs.size());
  for (const agent::MissionCommandLeg& l : command.legs) {
    msg::MissionLeg leg;
    leg.kind(l.kind == agent::MissionCommandLeg::Kind::kTo ? msg::LEG_TO : msg::LEG_VELOCITY);
    leg.east(l.value.x());
    leg.north(l.value.y());
    leg.duration_s(l.duration_s);
    leg.speed_mps(l.speed_mps);
    m.legs().push_back(leg);
  }
  return m;
}

std::variant<agent::MissionCommand, std::string> missionCommandOf(const msg::SwarmMission& m) {
  agent::MissionCommand command;
  switch (m.command()) {
    case msg::MISSION_LEGS:
      break;
    case msg::MISSION_HOLD:
      command.hold = true;
      break;
    default:
      return "unknown command kind " + std::to_string(static_cast<std::uint32_t>(m.command()));
  }
  // Not more than the agent will take: a flood of legs is refused on its count, without being copied first.
  if (m.legs().size() > agent::kMaxMissionLegs) {
    return std::to_string(m.legs().size()) + " legs; at most " + std::to_string(agent::kMaxMissionLegs);
  }
  command.legs.reserve(m.legs().size());
  for (std::size_t i = 0; i < m.legs().size(); ++i) {
    const msg::MissionLeg& leg = m.legs()[i];
    agent::MissionCommandLeg l;
    switch (leg.kind()) {
      case msg::LEG_VELOCITY:
        l.kind = agent::MissionCommandLeg::Kind::kVelocity;
        break;
      case msg::LEG_TO:
        l.kind = agent::MissionCommandLeg::Kind::kTo;
        break;
      default:
        return "leg " + std::to_string(i) + " has unknown kind " +
               std::to_string(static_cast<std::uint32_t>(leg.kind()));
    }
    l.value = agent::Vec2(leg.east(), leg.north());
    l.duration_s = leg.duration_s();
    l.speed_mps = leg.speed_mps();
    command.legs.push_back(l);
  }
  return command;
}

}  // namespace swa::wire
