// What the live view's pictures cost the monitor (swa_monitor --live draws them with the report's engine): the swarm
// from above for 8 and 64 UAVs, and the three metric plots over a full minute of 10 Hz rows. Google Benchmark; the
// results and what they mean per second of a run: BENCHMARKS.md.

#include <cmath>
#include <map>

#include <benchmark/benchmark.h>

#include "live_pictures.h"

namespace swa::live {
namespace {

SwarmScene ring(int n) {
  SwarmScene s;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    const double r = 10.0 * std::sqrt(static_cast<double>(n));
    s.uavs.push_back({i, r * std::cos(a), r * std::sin(a), 0.1, 0.0, true});
    s.links.emplace_back(i, (i + 1) % n);
    s.centres.push_back({i, 0.3 * std::cos(a), 0.3 * std::sin(a)});
  }
  return s;
}

void SwarmPicture(benchmark::State& state) {
  const SwarmScene scene = ring(static_cast<int>(state.range(0)));
  SwarmFrame frame;
  for (auto _ : state) benchmark::DoNotOptimize(swarmSvg(scene, frame.follow(scene)));
}
BENCHMARK(SwarmPicture)->Arg(8)->Arg(64)->Unit(benchmark::kMicrosecond);

void MetricPictures(benchmark::State& state) {
  MetricWindow window(60.0);
  for (int k = 0; k <= 600; ++k) {
    monitor::TimeSeriesRow row;
    row.t_s = 0.1 * k;
    row.d_nb_m = 10.0 + 0.2 * std::sin(0.05 * k);
    row.drift_mps = 0.05 + 0.01 * std::cos(0.03 * k);
    row.min_sep_m = 8.0 + 0.5 * std::sin(0.02 * k);
    row.nees_pos = 2.0 + std::sin(0.1 * k);
    window.add(row);
  }
  const monitor::MetricsConfig scoring;
  for (auto _ : state) benchmark::DoNotOptimize(metricPictures(window, scoring));
}
BENCHMARK(MetricPictures)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace swa::live

BENCHMARK_MAIN();
