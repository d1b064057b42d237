#pragma once
// A study: a scenario swept over a grid of parameter values, every grid point run for the same seeds
// (swa_batch --sweep KEY=V1,V2 ... --seeds N). The grid and how it is cut into shards (--shard I/N), with no I/O:
// a run is (grid point, seed), numbered point-major, and shard I of N takes every N-th run starting at I - 1, so
// expensive grid points (large swarms) are spread over every shard.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace swa::study {

struct Axis {
  std::string key;                  // a scenario key, as --set takes it ("uav_count", "agent.formation.k")
  std::vector<std::string> values;  // as given, in order
};

// A named set of overrides, e.g. a neighbourhood rule spelled out in full: one value of the axis "variant".
struct Variant {
  std::string name;
  std::vector<std::string> overrides;  // "KEY=VALUE", as --set takes them
};

// The axis of the variants is called this; its values are their names.
constexpr const char* kVariantAxis = "variant";

struct StudyPlan {
  std::vector<Axis> axes;         // in the order given; the first varies slowest; "variant" (if any) last
  std::vector<Variant> variants;  // what each value of the "variant" axis sets
  int seeds = 1;                  // seeds scenario.seed .. scenario.seed + seeds - 1 at every grid point
};

struct Shard {
  int index = 1;  // 1 .. count (Slurm's array task ids count from 1 in deploy/slurm/)
  int count = 1;
  bool whole() const { return count == 1; }
};

// An axis with its values checked: a key, at least one value, none empty, none twice (key and values trimmed). `what`
// names the source in the std::invalid_argument thrown ("--sweep 'uav_count=4,,8'", "study.sweep.uav_count (line 3,
// column 14)").
Axis makeAxis(std::string key, std::vector<std::string> values, const std::string& what);
// "KEY=V1,V2,..." -> an axis. Throws std::invalid_argument saying what is wrong (no '=', no key, an empty value, a
// value given twice).
Axis parseSweep(const std::string& text);
// "NAME:KEY=V,KEY=V,..." -> a variant. Throws std::invalid_argument saying what is wrong (no name, no override, an
// override without '=' or without a key, a key set twice).
Variant parseVariant(const std::string& text);
// A variant with its overrides checked as parseVariant checks them; `what` names the source in the exception.
Variant makeVariant(std::string name, std::vector<std::string> overrides, const std::string& what);
// The plan with `variants` as its last axis ("variant", in this order); none: the plan unchanged.
void setVariants(StudyPlan& plan, std::vector<Variant> variants);
// "I/N" with 1 <= I <= N. Throws std::invalid_argument.
Shard parseShard(const std::string& text);
// More runs than a study may have: each run's scenario and summary stay in memory until the study is written.
constexpr std::size_t kMaxRuns = 10'000'000;

// Problems of a plan as a whole (no axis, the same key swept twice, more than kMaxRuns runs, a variant that sets a
// swept key, a "variant" axis without its variants), one per entry.
std::vector<std::string> planProblems(const StudyPlan& plan);

std::size_t pointCount(const StudyPlan& plan);
std::size_t runCount(const StudyPlan& plan);
// The values of grid point `point` (one per axis).
std::vector<std::string> pointValues(const StudyPlan& plan, std::size_t point);
// The same as --set overrides: "KEY=VALUE" per axis, and for the "variant" axis every override of that variant.
std::vector<std::string> pointOverrides(const StudyPlan& plan, std::size_t point);

struct RunRef {
  std::size_t index = 0;  // point * seeds + seed_offset
  std::size_t point = 0;
  int seed_offset = 0;
};
// The runs of `shard`, in index order.
std::vector<RunRef> shardRuns(const StudyPlan& plan, const Shard& shard);

}  // namespace swa::study
