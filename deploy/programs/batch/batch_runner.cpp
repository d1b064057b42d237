#include "batch_runner.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

namespace swa::batch {

void runEach(const std::vector<sim::Scenario>& scenarios, int jobs, const RunDone& on_done,
             const std::atomic<bool>& stop) {
  const int count = static_cast<int>(scenarios.size());
  std::atomic<int> next{0};
  std::mutex done_mutex;
  std::exception_ptr failure;
  auto worker = [&] {
    for (int k = next++; k < count && !stop; k = next++) {
      try {
        RunResult r = runClosedLoop(scenarios[static_cast<std::size_t>(k)]);
        const std::lock_guard<std::mutex> lock(done_mutex);
        on_done(static_cast<std::size_t>(k), std::move(r));
      } catch (...) {
        const std::lock_guard<std::mutex> lock(done_mutex);
        if (!failure) failure = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  const int threads = std::max(1, std::min(jobs, count));
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

std::vector<RunResult> runSeeds(const sim::Scenario& scenario, int seeds, int jobs, const SeedDone& on_done,
                                const std::atomic<bool>& stop) {
  std::vector<sim::Scenario> scenarios(static_cast<std::size_t>(seeds), scenario);
  for (int k = 0; k < seeds; ++k)
    scenarios[static_cast<std::size_t>(k)].seed = scenario.seed + static_cast<std::uint64_t>(k);
  std::vector<RunResult> results(scenarios.size());
  runEach(
      scenarios, jobs,
      [&](std::size_t k, RunResult&& r) {
        if (on_done) on_done(r);
        results[k] = std::move(r);
      },
      stop);
  return results;
}

std::vector<RunResult> runSeeds(const sim::Scenario& scenario, int seeds, int jobs, const SeedDone& on_done) {
  const std::atomic<bool> never{false};
  return runSeeds(scenario, seeds, jobs, on_done, never);
}

}  // namespace swa::batch
