// Closed-loop speed: simulated seconds per CPU second of the in-process loop (sim + N agent cores + metrics at
// 10 Hz), one thread. Prints a table; medians of 5 repetitions. Usage: bench_closed_loop [scenario.yaml]

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include "closed_loop.h"
#include "swa/sim/scenario_io.h"

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : std::string(SWA_SOURCE_DIR) + "/deploy/scenarios/dropout_8.yaml";
  std::printf("scenario %s, 120 s simulated per run, 5 runs per N, one thread\n\n", path.c_str());
  std::printf("| N | CPU s per run (median) | simulated s per CPU s | per UAV per simulated s |\n");
  std::printf("|---|---|---|---|\n");
  for (int n : {4, 8, 16, 32}) {
    const swa::sim::Scenario s = swa::sim::loadScenario(path, {"uav_count=" + std::to_string(n), "duration_s=120"});
    std::vector<double> cpu;
    for (int rep = 0; rep < 5; ++rep) {
      const std::clock_t c0 = std::clock();
      const swa::batch::RunResult r = swa::batch::runClosedLoop(s);
      cpu.push_back(static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
      if (r.summary.steps == 0) return 1;  // keeps the run observable
    }
    std::sort(cpu.begin(), cpu.end());
    const double median = cpu[2];
    std::printf("| %d | %.4f | %.0fx | %.1f us |\n", n, median, s.duration_s / median, median / s.duration_s / n * 1e6);
  }
  return 0;
}
