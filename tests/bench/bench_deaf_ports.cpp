// What the deaf-port watch costs every SWA process (swa/dds/deaf_port_watch.h): finding its own shared-memory ports
// (once per participant) and a look among them (four a second), in a process that holds one participant, as an agent
// does. Google Benchmark; not a ctest.
//
//   ./build/bin/bench_deaf_ports --benchmark_repetitions=5 --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "process_support.h"
#include "swa/dds/options.h"
#include "swa/dds/participant.h"
#include "swa/dds/shm_ports.h"

namespace {

// One participant for the whole program, on a domain reserved among SWA's tests and benchmarks and in a swarm of its
// own (process_support.h): nobody else's samples reach it, and it writes none.
swa::dds::Participant& participant() {
  static const std::unique_ptr<swa::dds::Participant> p = [] {
    const int domain = swa::testing::testDomain();
    swa::testing::useOwnSwarm();
    return std::make_unique<swa::dds::Participant>("swa_bench_deaf_ports", domain, swa::dds::resolveProfilesFile());
  }();
  return *p;
}

void BM_FindOwnPorts(benchmark::State& state) {
  participant();
  for (auto _ : state) benchmark::DoNotOptimize(swa::dds::ownSharedMemoryPorts());
  state.counters["ports"] = static_cast<double>(swa::dds::ownSharedMemoryPorts().size());
}
BENCHMARK(BM_FindOwnPorts)->Unit(benchmark::kMicrosecond);

void BM_LookAmongOwnPorts(benchmark::State& state) {
  participant();
  const std::vector<int> own = swa::dds::ownSharedMemoryPorts();
  if (own.empty()) state.SkipWithError("this process has no shared-memory port (shared memory off?)");
  for (auto _ : state) benchmark::DoNotOptimize(swa::dds::deafSharedMemoryPorts(own));
}
BENCHMARK(BM_LookAmongOwnPorts)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
