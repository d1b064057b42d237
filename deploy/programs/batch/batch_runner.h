#pragma once
// Runs a scenario over many seeds on a small thread pool. Each seed is an independent closed loop, so the only
// shared state is the result slot of its seed and the console.

#include <atomic>
#include <functional>
#include <vector>

#include "closed_loop.h"

namespace swa::batch {

using SeedDone = std::function<void(const RunResult&)>;  // called under a lock as each seed finishes
// Called under a lock as each run finishes, with its position in the list; the result is the callee's.
using RunDone = std::function<void(std::size_t index, RunResult&& result)>;

// Runs every scenario of `scenarios` on `jobs` threads, each handed to `on_done` as it finishes (in any order): a
// study keeps only what it needs of each run. Once `stop` is set no further run starts. Rethrows the first failure
// after every thread has finished.
void runEach(const std::vector<sim::Scenario>& scenarios, int jobs, const RunDone& on_done,
             const std::atomic<bool>& stop);

// Seeds scenario.seed .. scenario.seed + seeds - 1; results in seed order whatever the completion order. Once `stop`
// is set no further seed starts (the running ones finish); the caller then has an incomplete set.
std::vector<RunResult> runSeeds(const sim::Scenario& scenario, int seeds, int jobs, const SeedDone& on_done,
                                const std::atomic<bool>& stop);
// Every seed, nothing stops it (tests, studies).
std::vector<RunResult> runSeeds(const sim::Scenario& scenario, int seeds, int jobs, const SeedDone& on_done);

}  // namespace swa::batch
