#pragma once
// What a study (or one shard of it) leaves in its directory, and how shards become the study:
//
//   study.json             the study id, the version that ran it, the plan, the base scenario (effective YAML), which
//                          shard, and every run's summary metrics (swa_batch's per-seed keys), in run order
//   runs.csv               (whole study only) the tidy table: one row per run, the swept keys, the seed, every metric
//   points/<k>/summary.json (whole study only) per grid point: its values, and the aggregate over its seeds
//   study.html             (whole study only) the key metrics against each swept key (study_html.h)
//
// A whole study's files are written from the same record a merge of its shards builds, so `swa_batch merge` of the
// shards writes byte for byte what one run of the whole study writes. No DDS, no simulation.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "study_plan.h"
#include "swa/monitor/summary_format.h"
#include "swa/run_record/run_dir.h"

namespace swa::study {

class StudyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RunRow {
  std::size_t index = 0;
  std::size_t point = 0;
  std::uint64_t seed = 0;
  std::vector<monitor::NamedValue> metrics;  // monitor::summaryFields of the run
};

struct StudyRecord {
  std::string study_id;
  std::string version;        // of the program that ran it
  std::string scenario;       // the scenario file given
  std::string scenario_yaml;  // the base scenario, effective (before the sweep's overrides)
  std::uint64_t first_seed = 0;
  StudyPlan plan;
  Shard shard;
  std::vector<RunRow> runs;  // by index
};

// The build's version: the project version and the commit it was built from, "-dirty" with uncommitted changes
// (build time).
std::string programVersion();
// A digest of everything that makes a study's results: version, base scenario, plan, first seed.
std::string studyId(const std::string& version, const std::string& scenario_yaml, const StudyPlan& plan,
                    std::uint64_t first_seed);

record::Json studyJson(const StudyRecord& study);
// Throws StudyError naming `source` and what is wrong.
StudyRecord studyFromJson(const record::Json& json, const std::string& source);

// The study the shards make together. Throws StudyError if they are of different studies or versions, if a run is in
// two of them, or if runs are missing (naming the shards that are).
StudyRecord mergeShards(const std::vector<StudyRecord>& shards);

// runs.csv.
std::string tidyCsv(const StudyRecord& study);
// points/<k>/summary.json of grid point `point`.
record::Json pointSummaryJson(const StudyRecord& study, std::size_t point);

// A shard's directory: study.json. Throws record::RunFileError.
void writeShard(const std::string& dir, const StudyRecord& shard);
// A whole study's directory: study.json, runs.csv, points/, study.html. Throws record::RunFileError.
void writeStudy(const std::string& dir, const StudyRecord& study);
// study.json of `dir`. Throws StudyError.
StudyRecord readStudy(const std::string& dir);
// Throws StudyError if `dir` already holds a study or a shard (study.json or points/): writing over it would leave
// the old study's grid points beside the new one's.
void refuseOldStudy(const std::string& dir);

}  // namespace swa::study
