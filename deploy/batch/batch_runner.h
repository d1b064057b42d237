#pragma once
// Runs a scenario over many seeds on a small thread pool. Each seed is an independent closed loop, so the only
// shared state is the result slot of its seed and the console.

#include <atomic>
#include <functional>
#include <vector>

#include "closed_loop.h"

namespace swa::batch {

using SeedDone = std::function<void(const RunResult&)>;  // called under a lock as each seed finishes

// Seeds scenario.seed .. scenario.seed + seeds - 1; results in seed order whatever the completion order. Once `stop`
// is set no further seed starts (the running ones finish); the caller then has an incomplete set.
std::vector<RunResult> runSeeds(const sim::Scenario& scenario, int seeds, int jobs, const SeedDone& on_done,
                                const std::atomic<bool>& stop);
// Every seed, nothing stops it (tests, studies).
std::vector<RunResult> runSeeds(const sim::Scenario& scenario, int seeds, int jobs, const SeedDone& on_done);

}  // namespace swa::batch
