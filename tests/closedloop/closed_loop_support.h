#pragma once
// Shared by the closed-loop tests: load a shipped scenario, run it over seeds, and read aggregate metrics.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "batch_runner.h"
#include "swa/monitor/summary_format.h"
#include "swa/sim/scenario_io.h"

namespace swa::batch::testing {

// r: the formation radius (and lattice spacing) of every shipped scenario.
inline constexpr double kR = 10.0;

// The sanitizer stage (ASan + UBSan, SWA_SANITIZED) runs these tests to find memory and undefined-behaviour errors on
// every code path they set up (every mode, rule and sensor model), not to re-check statistics (issue #42): there
// runSeeds runs kSanitizedSeeds seeds (both of the batch's workers busy) and kStatistics is false, so the assertions
// over the seeds (means, and orderings of means) are the Release suite's, on every seed. What must hold of every
// single run (no collision, one group, no rejected input, ANEES inside its band) is asserted in both builds: the
// runs are the same, bit for bit (test_golden.cpp, test_formation_guard.cpp).
#ifdef SWA_SANITIZED
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif
inline constexpr bool kStatistics = !kSanitized;
inline constexpr int kSanitizedSeeds = 2;

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

// Ten seeds by default (the minimum; kSanitizedSeeds in the sanitizer stage), two in parallel on this
// two-core machine.
// Every run, in both builds, must have flown the whole scenario and given finite figures.
inline Stats runSeeds(const sim::Scenario& s, int seeds = 10) {
  const int n = kStatistics ? seeds : std::min(seeds, kSanitizedSeeds);
  Stats stats{batch::runSeeds(s, n, 2, nullptr)};
  EXPECT_EQ(stats.runs.size(), static_cast<std::size_t>(n));
  for (const RunResult& r : stats.runs) {
    EXPECT_TRUE(!r.series.empty() && r.series.back().t_s >= s.duration_s - 1.0) << "seed " << r.seed;
    EXPECT_TRUE(std::isfinite(r.summary.mean_neighbor_distance_m) && std::isfinite(r.summary.drift_velocity_mps))
        << "seed " << r.seed;
  }
  return stats;
}

// The neighbourhood rules before issue #10, spelled out (the defaults are Gabriel + weighted fit + bias removal).
// `more` is appended.
inline std::vector<std::string> kNearest(int k, const std::vector<std::string>& more = {}) {
  std::vector<std::string> sets = {"agent.formation.neighbourhood=k_nearest", "agent.formation.k=" + std::to_string(k),
                                   "agent.formation.far_neighbour_weight=1", "agent.focal.bias_window_s=0"};
  sets.insert(sets.end(), more.begin(), more.end());
  return sets;
}

}  // namespace swa::batch::testing
