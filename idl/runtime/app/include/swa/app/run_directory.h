#pragma once
// A program's --out (swa_launch, swa_batch): the files of an earlier run are removed before the new run writes, so no
// file of the old run stays beside the new one's (a reused --out kept the old swa/, standalone/ and combine.log, issue
// #30). A program removes only what a run wrote: at its end it lists, in a marker file, the entries of --out that
// appeared during the run; the next run into that directory removes exactly those. Files of the user's (a log the
// shell redirects there, notes) are never touched.

#include <filesystem>
#include <set>
#include <string>

namespace swa::app {

// The file listing what the last run into a directory wrote.
inline constexpr const char* kRunMarker = ".swa_run_files";

// Removes what the marker in `out` lists, and the marker; nothing if `out` does not exist or has no marker (a
// directory of a run older than the marker keeps its files). Throws std::runtime_error if `out` is a file, or an
// entry cannot be removed.
void claimRunDirectory(const std::filesystem::path& out);

// The names of the entries of `out` (none if it does not exist).
std::set<std::string> entriesOf(const std::filesystem::path& out);

// Writes the marker into `out`: every entry now in it that is not in `before` (what the run wrote). Throws
// std::runtime_error if it cannot.
void markRunDirectory(const std::filesystem::path& out, const std::set<std::string>& before);

}  // namespace swa::app
