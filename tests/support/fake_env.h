#pragma once
// Shared by the tests of what a process reads from its environment: the variables a test sets, and nothing else.

#include <functional>
#include <map>
#include <optional>
#include <string>

namespace swa::testing {

// A getenv answered from `vars` alone (the shape of dds::EnvLookup), so the host's environment plays no part.
inline std::function<std::optional<std::string>(const std::string&)> fakeEnv(std::map<std::string, std::string> vars) {
  return [vars = std::move(vars)](const std::string& name) -> std::optional<std::string> {
    const auto it = vars.find(name);
    if (it == vars.end()) return std::nullopt;
    return it->second;
  };
}

}  // namespace swa::testing
