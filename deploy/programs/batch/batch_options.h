#pragma once
// Command line of swa_batch. Parsing is separate from main() so it can be tested and its errors are all reported
// at once, like the scenario's.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "swa/agent/config.h"

namespace swa::batch {

struct BatchOptions {
  std::string scenario_path;
  std::vector<std::string> overrides;  // --set k=v, in order
  int seeds = 1;                       // seeds scenario.seed, scenario.seed + 1, ...
  int jobs = 1;                        // seeds run in parallel
  std::string out_dir = "out/batch";
  std::optional<agent::Mode> compare;  // --compare standalone: the same seeds again in that mode
  std::vector<std::string> sweeps;     // --sweep KEY=V1,V2,...: a study over the grid of every sweep
  std::vector<std::string> variants;   // --variant NAME:KEY=V,...: one more axis of named sets of overrides
  std::string shard;                   // --shard I/N: only that slice of the study's runs
  bool jobs_given = false;
  bool seeds_given = false;  // --seeds given: it replaces a study section's seeds
  // swa_batch merge DIR... --out DIR: the shards' study.json files into the study's files (no simulation)
  bool merge = false;
  std::vector<std::string> merge_dirs;
  bool dry_run = false;  // check everything, print what would run, run nothing
  bool help = false;
  bool list_parameters = false;

  // A study by the command line (--sweep, --variant or --shard): the grid's results, not one scenario's. A scenario
  // file with a study section (study_section.h) is a study too.
  bool study() const { return !sweeps.empty() || !variants.empty() || !shard.empty(); }
};

// Throws std::invalid_argument listing every problem found.
BatchOptions parseBatchOptions(const std::vector<std::string>& args);
std::string batchUsage();

}  // namespace swa::batch
