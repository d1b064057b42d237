#include "batch_runner.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

namespace swa::batch {

std::vector<RunResult> runSeeds(const sim::Scenario& scenario, int seeds, int jobs, const SeedDone& on_done,
                                const std::atomic<bool>& stop) {
  std::vector<RunResult> results(static_cast<std::size_t>(seeds));
  std::atomic<int> next{0};
  std::mutex done_mutex;
  std::exception_ptr failure;
  auto worker = [&] {
    for (int k = next++; k < seeds && !stop; k = next++) {
      try {
        sim::Scenario s = scenario;
        s.seed = scenario.seed + static_cast<std::uint64_t>(k);
        RunResult r = runClosedLoop(s);
        const std::lock_guard<std::mutex> lock(done_mutex);
        if (on_done) on_done(r);
        results[static_cast<std::size_t>(k)] = std::move(r);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(done_mutex);
        if (!failure) failure = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  const int threads = std::max(1, std::min(jobs, seeds));
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  return results;
}

std::vector<RunResult> runSeeds(const sim::Scenario& scenario, int seeds, int jobs, const SeedDone& on_done) {
  const std::atomic<bool> never{false};
  return runSeeds(scenario, seeds, jobs, on_done, never);
}

}  // namespace swa::batch
