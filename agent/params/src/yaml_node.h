#pragma once
// Internal: how the readers (read.cpp, section.cpp) name a YAML node and where it was written, in messages.

#include <yaml-cpp/yaml.h>

#include <string>

namespace swa::params::detail {

inline const char* nodeKindName(const YAML::Node& node) {
  if (node.IsMap()) return "a map";
  if (node.IsSequence()) return "a sequence";
  if (node.IsNull()) return "nothing";
  return "a scalar";
}

// " (line L, column C)", or "" for a node built in code.
inline std::string locationOf(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  if (mark.is_null()) return {};
  return " (line " + std::to_string(mark.line + 1) + ", column " + std::to_string(mark.column + 1) + ")";
}

}  // namespace swa::params::detail
