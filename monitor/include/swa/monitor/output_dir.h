#pragma once
// Where a run's files go. Every program that writes a report checks the directory before it starts anything: a run
// that cannot be recorded is not worth starting, and a bad --out is a usage error (exit 2), found at once.

#include <string>

namespace swa::monitor {

// Creates `dir` (and its parents) and proves it writable with a probe file. Throws std::runtime_error naming the
// option (`what`, e.g. "--out") and the reason.
void prepareOutputDir(const std::string& dir, const std::string& what = "--out");

}  // namespace swa::monitor
