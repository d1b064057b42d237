#pragma once
// The `study:` section of a scenario file, so a study is one file under version control:
//
//   study:
//     seeds: 20                                      # repetitions of every grid point (swa_batch --seeds)
//     sweep:                                         # one axis per key, in this order (the first varies slowest)
//       uav_count: [4, 8, 16, 32]                    # any scenario key, as --set takes it
//       agent.formation.neighbourhood: [gabriel, k_nearest]
//     variants:                                      # one more axis, "variant", after the sweep's: named sets of
//       gabriel: {agent.formation.neighbourhood: gabriel, agent.focal.bias_window_s: 30}     # scenario keys, each
//       k3: {agent.formation.neighbourhood: k_nearest, agent.formation.k: 3}                # grid point runs each
//
// The scenario's loader skips the section (params::Schema::foreign_sections), so every other program runs the file
// as the base scenario. On swa_batch's command line, --sweep KEY=... replaces the file's values of KEY (in its place)
// or adds an axis after the file's, --variant NAME:KEY=V,... replaces the file's variant NAME or adds one, and --seeds
// replaces study.seeds.

#include <functional>
#include <string>
#include <vector>

#include "study_plan.h"

namespace swa::study {

struct StudySection {
  bool present = false;
  int seeds = 0;                  // 0: not given
  std::vector<Axis> axes;         // in file order
  std::vector<Variant> variants;  // in file order
};

// Throws params::ConfigError (source = path) listing every problem: an unknown entry, seeds not a whole number in
// [1, 100000], a sweep key without values or with an empty or repeated value, a variant's key given a list, the
// section not a map.
StudySection readStudySection(const std::string& scenario_path);

// The study's plan: the file's section with the command line's --sweep (each "KEY=V1,V2,..."), --variant (each
// "NAME:KEY=V,...") and --seeds (0: not given) on top; `fallback_seeds` when neither gives seeds. Keys are compared,
// and recorded, by their canonical name (`canonical`: the scenario's aliases resolved), so `--sweep agent.k=...`
// replaces the file's agent.formation.k. Throws std::invalid_argument listing every problem.
StudyPlan combinePlan(const StudySection& file, const std::vector<std::string>& sweeps,
                      const std::vector<std::string>& variants, int seeds, int fallback_seeds,
                      const std::function<std::string(const std::string&)>& canonical);

}  // namespace swa::study
