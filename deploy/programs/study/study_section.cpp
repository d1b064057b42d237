#include "study_section.h"

#include <algorithm>
#include <optional>
#include <stdexcept>

#include "swa/app/number.h"
#include "swa/params/error.h"
#include "swa/params/section.h"

namespace swa::study {
namespace {

constexpr int kMaxSeeds = 100000;  // as swa_batch --seeds
const std::string kSweep = "sweep.";
const std::string kVariants = "variants.";

// variants.NAME.KEY = VALUE (the YAML's nested maps flattened): one override of variant NAME.
void addVariantLeaf(const params::SectionLeaf& leaf, std::vector<Variant>& variants,
                    std::vector<std::string>& problems) {
  const std::string rest = leaf.key.substr(kVariants.size());
  const std::size_t dot = rest.find('.');
  const std::string name = rest.substr(0, dot);
  if (dot == std::string::npos || leaf.sequence || leaf.values.size() != 1) {
    problems.push_back("study." + leaf.key + leaf.where + ": a variant is a map of scenario keys to one value each, " +
                       "e.g. variants: {" + name + ": {agent.formation.k: 3}}");
    return;
  }
  auto it = std::find_if(variants.begin(), variants.end(), [&](const Variant& v) { return v.name == name; });
  if (it == variants.end()) it = variants.insert(variants.end(), Variant{name, {}});
  it->overrides.push_back(rest.substr(dot + 1) + "=" + leaf.values.front());
}

int seedsOf(const params::SectionLeaf& leaf, std::vector<std::string>& problems) {
  const std::string bad = "study.seeds must be a whole number in [1, " + std::to_string(kMaxSeeds) + "]";
  if (leaf.sequence || leaf.values.size() != 1) {
    problems.push_back(bad + ", got a list" + leaf.where);
    return 0;
  }
  const std::string& text = leaf.values.front();
  const std::optional<long long> n = app::parseInteger(text, 1, kMaxSeeds);
  if (!n) {
    problems.push_back(bad + ", got '" + text + "'" + leaf.where);
    return 0;
  }
  return static_cast<int>(*n);
}

}  // namespace

StudySection readStudySection(const std::string& scenario_path) {
  const params::Section section = params::readSection(scenario_path, "scenario", "study");
  StudySection s;
  s.present = section.present;
  std::vector<std::string> problems = section.problems;
  for (const params::SectionLeaf& leaf : section.leaves) {
    if (leaf.key == "seeds") {
      s.seeds = seedsOf(leaf, problems);
    } else if (leaf.key.rfind(kSweep, 0) == 0) {
      try {
        s.axes.push_back(makeAxis(leaf.key.substr(kSweep.size()), leaf.values, "study." + leaf.key + leaf.where));
      } catch (const std::invalid_argument& e) {
        problems.push_back(e.what());
      }
    } else if (leaf.key.rfind(kVariants, 0) == 0) {
      addVariantLeaf(leaf, s.variants, problems);
    } else {
      problems.push_back("unknown entry 'study." + leaf.key + "'" + leaf.where +
                         ": a study section holds seeds: N, sweep: {KEY: [V1, V2, ...], ...} and variants: "
                         "{NAME: {KEY: VALUE, ...}, ...}");
    }
  }
  for (Variant& v : s.variants) {
    try {
      v = makeVariant(v.name, v.overrides, "study.variants." + v.name);
    } catch (const std::invalid_argument& e) {
      problems.push_back(e.what());
    }
  }
  if (!problems.empty()) throw params::ConfigError(scenario_path, problems);
  return s;
}

StudyPlan combinePlan(const StudySection& file, const std::vector<std::string>& sweeps,
                      const std::vector<std::string>& variants, int seeds, int fallback_seeds,
                      const std::function<std::string(const std::string&)>& canonical) {
  StudyPlan plan;
  plan.axes = file.axes;
  for (Axis& a : plan.axes) a.key = canonical(a.key);
  plan.seeds = seeds > 0 ? seeds : file.seeds > 0 ? file.seeds : fallback_seeds;
  std::vector<std::string> problems;
  std::vector<std::string> given;  // keys the command line swept, to find one given twice there
  for (const std::string& text : sweeps) {
    try {
      Axis axis = parseSweep(text);
      axis.key = canonical(axis.key);
      if (axis.key == "seed") {
        problems.push_back("--sweep seed: seeds are a study's repetitions, give --seeds N instead");
        continue;
      }
      for (const std::string& key : given) {
        if (key == axis.key) problems.push_back("--sweep " + key + " given twice: give its values once");
      }
      given.push_back(axis.key);
      bool replaced = false;
      for (Axis& a : plan.axes) {
        if (a.key != axis.key) continue;
        a.values = axis.values;
        replaced = true;
      }
      if (!replaced) plan.axes.push_back(std::move(axis));
    } catch (const std::invalid_argument& e) {
      problems.push_back(e.what());
    }
  }
  for (const Axis& a : file.axes) {
    if (canonical(a.key) == "seed")
      problems.push_back("study.sweep.seed: seeds are a study's repetitions, give study.seeds N");
  }
  std::vector<Variant> all = file.variants;
  for (const std::string& text : variants) {
    try {
      Variant v = parseVariant(text);
      const auto same = std::find_if(all.begin(), all.end(), [&](const Variant& w) { return w.name == v.name; });
      if (same != all.end()) {
        *same = std::move(v);
      } else {
        all.push_back(std::move(v));
      }
    } catch (const std::invalid_argument& e) {
      problems.push_back(e.what());
    }
  }
  for (Variant& v : all) {
    for (std::string& o : v.overrides) {
      const std::size_t eq = o.find('=');
      const std::string key = canonical(o.substr(0, eq));
      if (key == "seed") problems.push_back("variant " + v.name + " sets the seed: seeds are a study's repetitions");
      o = key + o.substr(eq);
    }
  }
  setVariants(plan, std::move(all));
  for (const std::string& problem : planProblems(plan)) problems.push_back(problem);
  if (!problems.empty()) {
    std::string text;
    for (const std::string& problem : problems) text += (text.empty() ? "" : "\n") + problem;
    throw std::invalid_argument(text);
  }
  return plan;
}

}  // namespace swa::study
