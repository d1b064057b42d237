#pragma once
// Loading, validating, overriding and recording an AgentConfig.
//
// Every parameter is declared once (key, type, unit, bounds, meaning) in config_io.cpp; that one table drives
// the YAML loader, the `--set key=value` overrides, `--help` and the YAML dump. YAML is an implementation
// detail: nothing here includes yaml-cpp.
//
// File layout mirrors the struct: a top-level `mode` and one map per section, keyed by the field names of
// config.h, e.g.
//
//   mode: swa
//   formation:
//     radius_m: 10.0
//     k: 3
//
// Keys left out keep their defaults; an empty file is the default configuration. Every problem in a file
// (unknown keys, wrong types, out-of-range or non-finite values, invalid choices, violated cross-field
// constraints) is collected and reported together in one ConfigError.

#include <stdexcept>
#include <string>
#include <vector>

#include "swa/agent/config.h"

namespace swa::agent {

// All problems found in one configuration source (a file path, "<string>" or "--set").
// what() lists them one per line, each prefixed by the source: "agent.yaml: control.k_p = -1 is out of ...".
class ConfigError : public std::runtime_error {
 public:
  // Repeated problems are merged, long ones cut and at most 20 listed (param_file.h): a broken 10 MB file is one
  // screen of errors, not five million lines.
  ConfigError(std::string source, std::vector<std::string> problems);

  const std::string& source() const noexcept { return source_; }
  // One human-readable message per problem, without the source prefix. Each names the offending key.
  const std::vector<std::string>& problems() const noexcept { return problems_; }

 private:
  struct Summarised {};
  ConfigError(Summarised, std::string source, std::vector<std::string> problems);

  std::string source_;
  std::vector<std::string> problems_;
};

// Reads and parses a YAML file. Throws ConfigError (source = the path) when the file is missing, unreadable,
// not valid YAML, or describes an invalid configuration.
AgentConfig loadAgentConfig(const std::string& yaml_path);

// Parses YAML text on top of the defaults. `source_name` prefixes the messages of a ConfigError.
AgentConfig parseAgentConfig(const std::string& yaml_text, const std::string& source_name = "<string>");

// Sets one parameter from its command-line text, e.g. ("formation.k", "2"). The value is read as a YAML
// scalar, so the same type, bound and cross-field checks apply as in a file. Throws ConfigError
// (source "--set") and leaves `config` unchanged on any problem.
void applyOverride(AgentConfig& config, const std::string& dotted_key, const std::string& value);

// Applies "key=value" strings in order (the `--set` arguments); all problems are collected into one
// ConfigError (source "--set"), including malformed entries without '=' or with an empty key.
AgentConfig applyOverrides(AgentConfig config, const std::vector<std::string>& key_eq_value);

// Checks a configuration built in code against the same bounds and cross-field constraints as a file.
// Throws ConfigError (source = `source_name`) listing every violation.
void validateAgentConfig(const AgentConfig& config, const std::string& source_name = "<config>");

// Human-readable table of every parameter: key, type, unit, default, [min, max], meaning (for --help).
std::string describeParameters();

// The full effective configuration as YAML (every key, with its unit as a comment). Values are printed
// with enough digits to round-trip exactly: parseAgentConfig(toYaml(c)) reproduces c.
std::string toYaml(const AgentConfig& config);

}  // namespace swa::agent
