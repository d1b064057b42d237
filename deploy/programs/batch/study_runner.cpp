#include "study_runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <unordered_map>

#include "batch_runner.h"
#include "swa/params/error.h"
#include "swa/sim/scenario_io.h"

namespace swa::batch {
namespace {

std::string describe(const study::StudyPlan& plan, std::size_t point) {
  std::string text;
  const std::vector<std::string> v = study::pointValues(plan, point);
  for (std::size_t k = 0; k < v.size(); ++k) text += (k ? " " : "") + plan.axes[k].key + "=" + v[k];
  return text;
}

std::string duration(double s) {
  const auto total = static_cast<long long>(s + 0.5);
  char text[32];
  if (total >= 3600) {
    std::snprintf(text, sizeof text, "%lldh%02lldm", total / 3600, total % 3600 / 60);
  } else {
    std::snprintf(text, sizeof text, "%lldm%02llds", total / 60, total % 60);
  }
  return text;
}

double metric(const monitor::Summary& s, const char* key) {
  for (const monitor::NamedValue& f : monitor::summaryFields(s)) {
    if (f.key == key) return f.value;
  }
  return monitor::kNaN;
}

}  // namespace

PreparedStudy prepareStudy(const BatchOptions& o, const study::StudySection& section) {
  PreparedStudy p;
  std::vector<std::string> problems;
  try {
    p.record.plan = study::combinePlan(section, o.sweeps, o.variants, o.seeds_given ? o.seeds : 0, o.seeds,
                                       sim::canonicalScenarioKey);
  } catch (const std::invalid_argument& e) {
    problems.push_back(e.what());
  }
  // A key set by --set and by a variant: which should win is the user's to say, not ours to guess.
  for (const study::Variant& v : p.record.plan.variants) {
    for (const std::string& vo : v.overrides) {
      const std::string key = vo.substr(0, vo.find('='));
      for (const std::string& so : o.overrides) {
        if (sim::canonicalScenarioKey(so.substr(0, so.find('='))) == key) {
          problems.push_back("--set " + so + " and variant " + v.name + " both set " + key + ": set it in one place");
        }
      }
    }
  }
  if (!o.shard.empty()) {
    try {
      p.record.shard = study::parseShard(o.shard);
    } catch (const std::invalid_argument& e) {
      problems.push_back(e.what());
    }
  }
  if (!problems.empty()) {
    std::string text;
    for (const std::string& problem : problems) text += (text.empty() ? "" : "\n") + problem;
    throw std::invalid_argument(text);
  }
  const study::StudyPlan& plan = p.record.plan;

  const sim::Scenario base = sim::loadScenario(o.scenario_path, o.overrides);
  p.record.scenario = o.scenario_path;
  p.record.scenario_yaml = sim::scenarioToYaml(base);
  p.record.first_seed = base.seed;
  p.record.version = study::programVersion();
  p.record.study_id = study::studyId(p.record.version, p.record.scenario_yaml, plan, base.seed);
  // Every grid point's scenario now: a bad value must stop the study before hours of runs, not in the middle.
  // Two grid points that make the same scenario (a key swept under two names, "0.1" and "0.10") would label equal
  // runs with different values: refused, as is a point that moves the seed (the study's repetitions).
  std::vector<std::string> point_problems;
  std::unordered_map<std::size_t, std::size_t> point_of_hash;
  for (std::size_t point = 0; point < study::pointCount(plan) && point_problems.size() < 10; ++point) {
    std::vector<std::string> overrides = o.overrides;
    for (const std::string& s : study::pointOverrides(plan, point)) overrides.push_back(s);
    try {
      p.point_scenarios.push_back(sim::loadScenario(o.scenario_path, overrides));
    } catch (const params::ConfigError& e) {
      point_problems.push_back("grid point " + describe(plan, point) + ": " + e.what());
      continue;
    }
    const sim::Scenario& s = p.point_scenarios.back();
    if (s.seed != base.seed) {
      point_problems.push_back("grid point " + describe(plan, point) +
                               " sets the seed: seeds are a study's repetitions, give --seeds N");
      continue;
    }
    const std::string yaml = sim::scenarioToYaml(s);
    const auto [it, fresh] = point_of_hash.emplace(std::hash<std::string>{}(yaml), point);
    if (!fresh && sim::scenarioToYaml(p.point_scenarios[it->second]) == yaml) {
      point_problems.push_back("grid points " + describe(plan, it->second) + " and " + describe(plan, point) +
                               " are the same scenario: is a key swept under two names (an alias), or a value "
                               "given twice in two spellings?");
    }
  }
  if (!point_problems.empty()) {
    std::string text;
    for (const std::string& problem : point_problems) text += (text.empty() ? "" : "\n") + problem;
    throw std::invalid_argument(text);
  }
  p.runs = study::shardRuns(plan, p.record.shard);
  return p;
}

void printStudyPlan(const PreparedStudy& p) {
  const study::StudyPlan& plan = p.record.plan;
  std::printf("study %s (version %s)\nscenario %s, seeds %llu..%llu at every grid point\n", p.record.study_id.c_str(),
              p.record.version.c_str(), p.record.scenario.c_str(), static_cast<unsigned long long>(p.record.first_seed),
              static_cast<unsigned long long>(p.record.first_seed + static_cast<std::uint64_t>(plan.seeds) - 1));
  for (const study::Axis& a : plan.axes) {
    if (a.key == study::kVariantAxis) continue;
    std::string values;
    for (const std::string& v : a.values) values += (values.empty() ? "" : ", ") + v;
    std::printf("sweep %s: %s\n", a.key.c_str(), values.c_str());
  }
  for (const study::Variant& v : plan.variants) {
    std::string overrides;
    for (const std::string& o : v.overrides) overrides += (overrides.empty() ? "" : ", ") + o;
    std::printf("variant %s: %s\n", v.name.c_str(), overrides.c_str());
  }
  std::printf("%zu grid point(s) x %d seed(s) = %zu runs; shard %d/%d: %zu runs\n", study::pointCount(plan), plan.seeds,
              study::runCount(plan), p.record.shard.index, p.record.shard.count, p.runs.size());
}

std::vector<sim::Scenario> runScenarios(const PreparedStudy& prepared) {
  std::vector<sim::Scenario> scenarios;
  for (const study::RunRef& r : prepared.runs) {
    sim::Scenario s = prepared.point_scenarios[r.point];
    s.seed = prepared.record.first_seed + static_cast<std::uint64_t>(r.seed_offset);
    scenarios.push_back(std::move(s));
  }
  return scenarios;
}

int runStudy(const BatchOptions& o, const PreparedStudy& prepared, int jobs, const std::atomic<bool>& stop) {
  const study::StudyPlan& plan = prepared.record.plan;
  const std::vector<sim::Scenario> scenarios = runScenarios(prepared);
  std::printf("swa_batch: study %s: %zu grid point(s) x %d seed(s) = %zu runs; shard %d/%d: %zu runs on %d job(s)\n",
              prepared.record.study_id.c_str(), study::pointCount(plan), plan.seeds, study::runCount(plan),
              prepared.record.shard.index, prepared.record.shard.count, scenarios.size(), jobs);
  std::fflush(stdout);

  study::StudyRecord record = prepared.record;
  record.runs.resize(prepared.runs.size());
  // The ETA weighs each run by what it costs, not one run as another: counting runs said 3-4 s for most of a 28 s
  // study. A run costs its UAV-steps times what a UAV's step costs, which grows with the neighbours it tracks: about
  // 20 + n units, n the neighbours within sensor range (at most N - 1; in a lattice of spacing s and range R about
  // 3.6 (R/s)^2). Measured here: a 64-UAV run of 120 s takes 55 times a 4-UAV one, as this model says.
  std::vector<double> cost(scenarios.size());
  double cost_left = 0.0, cost_done = 0.0;
  for (std::size_t k = 0; k < scenarios.size(); ++k) {
    const sim::Scenario& s = scenarios[k];
    const double in_range = 3.6 * std::pow(s.mps.range_m / std::max(s.formation.spacing_m, 1e-3), 2.0);
    const double neighbours = std::min(static_cast<double>(s.uav_count - 1), in_range);
    cost[k] = static_cast<double>(s.uav_count) * (20.0 + neighbours) * s.duration_s * s.dynamics.rate_hz;
    cost_left += cost[k];
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::size_t done = 0;
  runEach(
      scenarios, jobs,
      [&](std::size_t k, RunResult&& r) {
        const study::RunRef& ref = prepared.runs[k];
        record.runs[k] = {ref.index, ref.point, r.seed, monitor::summaryFields(r.summary)};
        ++done;
        cost_done += cost[k];
        cost_left -= cost[k];
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const double eta = cost_done > 0.0 ? elapsed / cost_done * std::max(cost_left, 0.0) : 0.0;
        std::printf("[%*zu/%zu] %s seed %llu  d_NB %.2f m  drift %.3f m/s  collisions %.0f  ETA %s\n",
                    static_cast<int>(std::to_string(scenarios.size()).size()), done, scenarios.size(),
                    describe(plan, ref.point).c_str(), static_cast<unsigned long long>(r.seed),
                    metric(r.summary, "mean_neighbor_distance_m"), metric(r.summary, "drift_velocity_mps"),
                    metric(r.summary, "collisions"), duration(eta).c_str());
        std::fflush(stdout);
      },
      stop);
  if (stop) {
    std::fprintf(stderr, "swa_batch: interrupted before every run of the study ran: nothing written\n");
    return 3;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (record.shard.whole()) {
    study::writeStudy(o.out_dir, record);
    // The page to open first, on a line of its own: the last thing the console shows.
    std::printf("swa_batch: %zu runs in %s; wrote %s/runs.csv, %s/points/, %s/study.json\n", record.runs.size(),
                duration(wall).c_str(), o.out_dir.c_str(), o.out_dir.c_str(), o.out_dir.c_str());
    std::printf("swa_batch: study: %s/study.html\n", o.out_dir.c_str());
  } else {
    study::writeShard(o.out_dir, record);
    std::printf("swa_batch: shard %d/%d: %zu runs in %s; wrote %s/study.json (swa_batch merge the shards)\n",
                record.shard.index, record.shard.count, record.runs.size(), duration(wall).c_str(), o.out_dir.c_str());
  }
  return 0;
}

int runMerge(const BatchOptions& o) {
  try {
    std::vector<study::StudyRecord> shards;
    for (const std::string& dir : o.merge_dirs) shards.push_back(study::readStudy(dir));
    const study::StudyRecord merged = study::mergeShards(shards);
    study::refuseOldStudy(o.out_dir);
    study::writeStudy(o.out_dir, merged);
    std::printf("swa_batch: merged %zu shard(s) of study %s: %zu runs into %s\n", shards.size(),
                merged.study_id.c_str(), merged.runs.size(), o.out_dir.c_str());
    std::printf("swa_batch: study: %s/study.html\n", o.out_dir.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "swa_batch merge: %s\n", e.what());
    return 2;
  }
}

}  // namespace swa::batch
