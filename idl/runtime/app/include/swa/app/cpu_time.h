#pragma once
// The CPU time this process has used so far. Every SWA program prints it when it ends, so that what one part of a
// run costs (the agents, the simulator, the monitor with its recording) is read from the logs (bench_scale,
// BENCHMARKS.md), not estimated.

#include <sys/resource.h>

#include <cstdio>
#include <string>

namespace swa::app {

struct CpuTime {
  double user_s = 0.0, system_s = 0.0;
  double total_s() const { return user_s + system_s; }
};

inline CpuTime processCpuTime() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return {};
  const auto seconds = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
  };
  return {seconds(usage.ru_utime), seconds(usage.ru_stime)};
}

// "<program>: 1.234 s of CPU time (user 1.000 s, system 0.234 s)", the line bench_scale reads.
inline std::string cpuTimeLine(const std::string& program) {
  const CpuTime t = processCpuTime();
  char text[160];
  std::snprintf(text, sizeof text, "%.3f s of CPU time (user %.3f s, system %.3f s)", t.total_s(), t.user_s,
                t.system_s);
  return program + ": " + text;
}

}  // namespace swa::app
