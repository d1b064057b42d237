#pragma once
// Shared by the closed-loop tests: load a shipped scenario, run it over seeds, and read aggregate metrics.

#include <string>
#include <vector>

#include "batch_runner.h"
#include "swa/monitor/summary_format.h"
#include "swa/sim/scenario_io.h"

namespace swa::batch::testing {

// r: the formation radius (and lattice spacing) of every shipped scenario.
inline constexpr double kR = 10.0;

inline sim::Scenario shipped(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return sim::loadScenario(std::string(SWA_SOURCE_DIR) + "/deploy/scenarios/" + name + ".yaml", overrides);
}

struct Stats {
  std::vector<RunResult> runs;
  double mean(const std::string& key) const { return stat(key).mean; }
  double max(const std::string& key) const { return stat(key).max; }
  double min(const std::string& key) const { return stat(key).min; }
  monitor::Statistic stat(const std::string& key) const {
    std::vector<monitor::Summary> s;
    for (const auto& r : runs) s.push_back(r.summary);
    const monitor::Aggregate a = monitor::aggregate(s);
    const monitor::Statistic* st = a.find(key);
    return st ? *st : monitor::Statistic{};
  }
};

// Ten seeds by default (the minimum), two in parallel on this two-core machine.
inline Stats runSeeds(const sim::Scenario& s, int seeds = 10) { return Stats{batch::runSeeds(s, seeds, 2, nullptr)}; }

// The neighbourhood rules before issue #10, spelled out (the defaults are Gabriel + weighted fit + bias removal).
// `more` is appended.
inline std::vector<std::string> kNearest(int k, const std::vector<std::string>& more = {}) {
  std::vector<std::string> sets = {"agent.formation.neighbourhood=k_nearest", "agent.formation.k=" + std::to_string(k),
                                   "agent.formation.far_neighbour_weight=1", "agent.focal.bias_window_s=0"};
  sets.insert(sets.end(), more.begin(), more.end());
  return sets;
}

}  // namespace swa::batch::testing
