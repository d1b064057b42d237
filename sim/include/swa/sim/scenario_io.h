#pragma once
// Loading, validating, overriding and recording a Scenario (sim/include/swa/sim/scenario.h).
//
// Every scenario parameter is declared once (key, type, unit, bounds, meaning) in scenario_io.cpp; the agent
// section reuses the agent's own table (agent/include/swa/agent/config_io.h). YAML is an implementation
// detail: nothing here includes yaml-cpp.
//
// File layout: top-level `uav_count`, `seed`, `duration_s`, then one map per section keyed by the field names
// of scenario.h, and an `agent:` map in the layout of the agent configuration file, e.g.
//
//   uav_count: 8
//   gnss:
//     dropout_start_s: 10.0
//     keep_uavs: [0]
//   agent:
//     mode: anchored
//     k: 2              # shortcut for agent.formation.k
//     circle_fit: fixed_radius  # shortcut for agent.formation.circle_fit
//
// Rules beyond the per-key bounds:
//   - `agent.k` / `agent.circle_fit` are shortcuts; giving a shortcut and its long form in one file is an error
//     (a `--set` of either form replaces whatever the file gave for the parameter).
//   - Unless `agent.formation.radius_m` is given, it is set to `formation.spacing_m`.
//   - `gnss.dropout_end_s` may be `.inf` (or left out): GNSS is never restored. No other key accepts infinity.
//   - imu/mps/gnss `rate_hz` must each divide `dynamics.rate_hz` exactly; dropout_end_s > dropout_start_s;
//     `gnss.keep_uavs` are distinct indices in [0, uav_count); every `gnss.windows` entry names a UAV in
//     [0, uav_count) and has end_s > start_s; formation.spacing_m < mps.range_m.
//
// Every problem (file, YAML syntax, unknown keys with a did-you-mean, wrong types, bounds with units, non-finite
// values, invalid choices, malformed or invalid `--set`, cross-field rules) is reported together in one
// swa::agent::ConfigError whose source is the file path (or `source` of parseScenario). File problems carry
// "(line L, column C)", override problems "(from --set key=value)".

#include <string>
#include <vector>

#include "swa/agent/config_io.h"  // swa::agent::ConfigError
#include "swa/sim/scenario.h"

namespace swa::sim {

// Reads a scenario file, applies the `--set` overrides ("dotted.key=value", in order; a later one wins), then
// validates the result. Throws swa::agent::ConfigError (source = `path`) listing every problem.
Scenario loadScenario(const std::string& path, const std::vector<std::string>& overrides = {});

// As loadScenario, from YAML text; `source` names the text in the error messages. An empty text is the default
// scenario.
Scenario parseScenario(const std::string& yaml_text, const std::string& source,
                       const std::vector<std::string>& overrides = {});

// The full effective scenario as commented YAML (every key, units in comments, agent section in long form with
// an explicit agent.formation.radius_m). Reals are written to round-trip exactly:
// scenarioToYaml(parseScenario(scenarioToYaml(s), ...)) == scenarioToYaml(s) for every valid scenario.
std::string scenarioToYaml(const Scenario& scenario);

// Human-readable table of every scenario parameter (key, type, unit, default, range, meaning), the cross-field
// rules, and the agent parameters accepted under `agent.` (for --help).
std::string describeScenarioParameters();

}  // namespace swa::sim
