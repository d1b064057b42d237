#pragma once

// Internal: the yaml-cpp side of the helpers shared by the parameter loaders (see param_text.h). Includes
// yaml-cpp, so only .cpp files of targets that link yaml-cpp include it, never a public header.

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <optional>
#include <string>

namespace swa::agent::param {

// "a map", "a sequence", "nothing" or "a scalar".
const char* nodeKindName(const YAML::Node& node);

// A quoted scalar ("10") or an explicit !!str: a string, never a number.
bool isQuoted(const YAML::Node& scalar);

// " (line L, column C)" of the node in its document, or "" if it has no position.
std::string locationOf(const YAML::Node& node);

// "invalid YAML at line L, column C: <what>" (the position left out if unknown).
std::string describeYamlException(const YAML::Exception& e);

// Reads `value`, the value of the numeric parameter `name`, as a number into `number` (parseNumber); if it is not a
// plain scalar that parses as one, returns why, naming what was expected (`expected`, e.g. "an integer within
// [1, 16]"). Whether the number is valid for the parameter is the caller's check (numberProblem).
std::optional<std::string> readNumber(const YAML::Node& value, const std::string& name, const std::string& expected,
                                      double& number);

// Map keys in the document, counted up to `limit` + 1. A parameter file has about a hundred; a document with
// thousands is not one (each unknown key costs a spelling suggestion), so the loaders refuse it up front.
constexpr std::size_t kMaxKeys = 2000;
std::size_t countKeys(const YAML::Node& node, std::size_t limit = kMaxKeys);

}  // namespace swa::agent::param
