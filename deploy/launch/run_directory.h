#pragma once
// swa_launch's --out: a directory of one run. An earlier launch's directory is emptied before the new run writes, so
// no file of the old run stays beside the new one's (a reused --out kept the old swa/, standalone/ and combine.log,
// issue #30); a directory that holds anything else is refused, since a launch never deletes what it did not write.

#include <filesystem>

namespace swa::launch {

// The file that marks a directory as swa_launch's (written by markRunDirectory).
inline constexpr const char* kRunMarker = ".swa_launch_run";

// Nothing, if `out` does not exist or is empty; empties it if it holds an earlier launch's run (the marker, or, from
// before the marker, a logs/ folder with a scenario.yaml or report.html beside it). Throws std::runtime_error, having
// touched nothing, if `out` is a file or a directory with anything else in it.
void claimRunDirectory(const std::filesystem::path& out);

// Writes the marker into `out` (which must exist). Throws std::runtime_error if it cannot.
void markRunDirectory(const std::filesystem::path& out);

}  // namespace swa::launch
