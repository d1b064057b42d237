#pragma once
// The rules between scenario parameters (a sensor rate that must divide the step rate, a GNSS outage that must not be
// empty, ...) and their text in --help, apart from scenario_io.cpp's table of the parameters themselves.

#include <vector>

#include "swa/params/schema.h"

namespace swa::sim {

// The rules between scenario parameters (the agent's own come with its table).
std::vector<params::Check> scenarioChecks();
// The same rules as told by the scenario's parameter description (describeScenarioParameters).
const char* scenarioRuleNotes();

}  // namespace swa::sim
