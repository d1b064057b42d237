#pragma once
// Loading, validating, overriding and recording an AgentConfig. Every parameter is declared once (key, type, unit,
// bounds, meaning) in config_io.cpp's table, which the parameter engine (swa/params) turns into the YAML loader,
// the `--set key=value` overrides, `--parameters` and the dump; the scenario mounts the same table under `agent.`.
//
// File layout mirrors the struct: a top-level `mode` and one map per section, keyed by the field names of
// config.h, e.g.
//
//   mode: swa
//   formation:
//     radius_m: 10.0
//     neighbourhood: k_nearest
//     k: 3
//
// Keys left out keep their defaults; an empty file is the default configuration. A key that the chosen mode
// ignores (k with the gabriel rule, ...: params::Applies) is an error when given. Every problem is reported
// together in one ConfigError (swa/params/engine.h).

#include <string>
#include <vector>

#include "swa/agent/config.h"
#include "swa/params/error.h"
#include "swa/params/table.h"

namespace swa::agent {

using ConfigError = params::ConfigError;

// The parameter table of the agent configuration.
const params::Table<AgentConfig>& configTable();
// Its rules between parameters (a mission's legs against its speed limit), with every key under `prefix` ("agent."
// where the scenario mounts the table: a mounted table's checks are the outer schema's).
std::vector<params::Check> configChecks(const std::string& prefix);

// Reads a YAML file. Throws ConfigError (source = the path) when the file is missing, unreadable, not valid YAML,
// or describes an invalid configuration.
AgentConfig loadAgentConfig(const std::string& yaml_path);

// Parses YAML text on top of the defaults. `source_name` prefixes the messages of a ConfigError.
AgentConfig parseAgentConfig(const std::string& yaml_text, const std::string& source_name = "<string>");

// Sets one parameter from its command-line text, e.g. ("formation.k", "2"), with the same checks as a file.
// Throws ConfigError (source "--set") and leaves `config` unchanged on any problem.
void applyOverride(AgentConfig& config, const std::string& dotted_key, const std::string& value);

// Applies "key=value" strings in order (the `--set` arguments); all problems in one ConfigError (source "--set").
AgentConfig applyOverrides(AgentConfig config, const std::vector<std::string>& key_eq_value);

// Checks a configuration built in code against the same bounds and rules as a file.
void validateAgentConfig(const AgentConfig& config, const std::string& source_name = "<config>");

// Every parameter: key, type, unit, default, [min, max], meaning (for --parameters).
std::string describeParameters();

// The full configuration as commented YAML that parses back to exactly `config`.
std::string toYaml(const AgentConfig& config);

}  // namespace swa::agent
