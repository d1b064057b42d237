#pragma once
// Loading, validating, overriding and recording a Scenario (sim/include/swa/sim/scenario.h). Every scenario
// parameter is declared once in scenario_io.cpp's table; the `agent:` section is the agent's own table
// (swa/agent/config_io.h) mounted under `agent.`, so both are read by the one parameter engine (swa/params).
//
// File layout: top-level `uav_count`, `seed`, `duration_s`, then one map per section keyed by the field names of
// scenario.h, and an `agent:` map in the layout of the agent configuration file, e.g.
//
//   uav_count: 8
//   gnss:
//     dropout_start_s: 10.0
//     keep_uavs: [0]
//   agent:
//     mode: anchored
//     formation: {neighbourhood: k_nearest}
//     k: 2              # alias of agent.formation.k
//
// Rules beyond the per-key bounds:
//   - `agent.k` / `agent.circle_fit` are aliases of agent.formation.k / agent.formation.circle_fit; giving both
//     spellings in one file is an error (a `--set` of either replaces whatever the file gave).
//   - Unless `agent.formation.radius_m` is given, it is set to `formation.spacing_m`.
//   - A key that the chosen mode ignores (params::Applies: agent.k with gabriel, clock.speed in lockstep, ...) is
//     an error when given, unless the file gave it and a --set turned it off.
//   - `gnss.dropout_end_s` may be `.inf` (or left out): GNSS is never restored.
//   - imu/mps/gnss `rate_hz` must each divide `dynamics.rate_hz` exactly; dropout_end_s > dropout_start_s;
//     `gnss.keep_uavs` are distinct indices in [0, uav_count); every `gnss.windows` entry names a UAV in
//     [0, uav_count) and has end_s > start_s; formation.spacing_m < mps.range_m.
//
// Every problem is reported together in one ConfigError whose source is the file path (or `source`).

#include <string>
#include <vector>

#include "swa/params/error.h"
#include "swa/sim/scenario.h"

namespace swa::sim {

// Reads a scenario file, applies the `--set` overrides ("dotted.key=value", in order; a later one wins), then
// validates the result. Throws params::ConfigError (source = `path`) listing every problem.
Scenario loadScenario(const std::string& path, const std::vector<std::string>& overrides = {});

// As loadScenario, from YAML text; `source` names the text in the error messages. An empty text is the default
// scenario.
Scenario parseScenario(const std::string& yaml_text, const std::string& source,
                       const std::vector<std::string>& overrides = {});

// As parseScenario, for a scenario a program wrote (a recording's, perhaps of a version whose dump gave every key):
// keys that the scenario's own modes turn off are not refused from it.
Scenario parseRecordedScenario(const std::string& yaml_text, const std::string& source,
                               const std::vector<std::string>& overrides = {});

// The full effective scenario as commented YAML (every key, agent.formation.radius_m explicit) that reads back to
// exactly `scenario`: a run directory's scenario.yaml.
std::string scenarioToYaml(const Scenario& scenario);

// Every scenario parameter (key, type, unit, default, range, meaning), the agent's under `agent.`, and the rules.
std::string describeScenarioParameters();

// A key's canonical name: an alias becomes the key it stands for (agent.k -> agent.formation.k); any other key, known
// or not, is returned unchanged.
std::string canonicalScenarioKey(const std::string& key);

}  // namespace swa::sim
