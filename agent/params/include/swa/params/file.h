#pragma once

// Internal: how the parameter loaders (agent configuration, scenario) read a file and word their problems, so a
// hostile or mistaken file gets a clear error instead of a hang or gigabytes: only regular files (not a device,
// pipe or socket: /dev/zero, /dev/urandom), at most kMaxFileBytes, text without NUL bytes. And a list of problems
// stays readable: repeats are counted once, at most kMaxProblems are listed, long messages are cut.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace swa::params {

constexpr std::size_t kMaxFileBytes = 1 << 20;  // 1 MiB: the full default scenario is 5 kB
constexpr std::size_t kMaxProblems = 20;
constexpr std::size_t kMaxProblemChars = 300;

// The file's text, or nullopt with `problem` set ("is a device or pipe, not a <kind> file", ...). `kind` names the
// file in messages, e.g. "scenario".
std::optional<std::string> readTextFile(const std::string& path, const std::string& kind, std::string& problem);

// Identical problems merged ("... (3 times)"), each cut to kMaxProblemChars, at most kMaxProblems kept and the rest
// counted in a last line.
std::vector<std::string> summariseProblems(const std::vector<std::string>& problems);

}  // namespace swa::params
