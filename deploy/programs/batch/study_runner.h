#pragma once
// swa_batch's study mode (--sweep, --shard) and `swa_batch merge`: the grid's scenarios built and checked before
// anything runs, every run of the shard on the thread pool with a progress line, the study's files
// (deploy/programs/study).

#include <atomic>
#include <vector>

#include "batch_options.h"
#include "study_record.h"
#include "study_section.h"
#include "swa/sim/scenario.h"

namespace swa::batch {

struct PreparedStudy {
  study::StudyRecord record;                   // id, version, plan, base scenario, shard; no runs yet
  std::vector<study::RunRef> runs;             // of this shard
  std::vector<sim::Scenario> point_scenarios;  // per grid point (seed: the first)
};

// The plan (the scenario file's study section with --sweep and --seeds on top), the base scenario and every grid
// point's; throws std::invalid_argument (bad sweeps or shard, a grid point's scenario naming its values) or
// params::ConfigError (the base scenario) listing every problem.
PreparedStudy prepareStudy(const BatchOptions& options, const study::StudySection& section);

// What the study (or shard) would run: its id, the grid and the runs, on stdout.
void printStudyPlan(const PreparedStudy& study);

// The scenario of each run of the shard, in the order of study.runs: its grid point's, with its seed.
std::vector<sim::Scenario> runScenarios(const PreparedStudy& study);

// Runs the shard's runs on `jobs` threads and writes the study (whole) or the shard's study.json into
// options.out_dir. Returns the exit status (0; 3 interrupted: nothing written).
int runStudy(const BatchOptions& options, const PreparedStudy& study, int jobs, const std::atomic<bool>& stop);

// swa_batch merge: returns 0, or 2 with the reason on stderr.
int runMerge(const BatchOptions& options);

}  // namespace swa::batch
