#include "swa/agent/config.h"

namespace swa::agent {
namespace {

template <class Enum, std::size_t N>
std::string nameIn(const std::pair<Enum, const char*> (&names)[N], Enum value) {
  for (const auto& [v, name] : names) {
    if (v == value) return name;
  }
  return "unknown";
}

}  // namespace

std::string toString(Mode mode) { return nameIn(kModeNames, mode); }
std::string toString(CircleFit fit) { return nameIn(kCircleFitNames, fit); }
std::string toString(NeighbourhoodRule rule) { return nameIn(kNeighbourhoodRuleNames, rule); }
std::string toString(DetectionInput input) { return nameIn(kDetectionInputNames, input); }
std::string toString(ImuSource source) { return nameIn(kImuSourceNames, source); }
std::string toString(MissionStart start) { return nameIn(kMissionStartNames, start); }

}  // namespace swa::agent
