#pragma once
// What the benchmarks read of processes and samples and how they print it: medians and quantiles, the load average,
// a live process's memory and CPU time (proc(5)), the children of a process, elapsed time, table numbers. Shared by
// bench_dds and bench_scale.

#include <dirent.h>
#include <sys/types.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "process_support.h"

namespace swa::bench {

using testing::readFile;
using Clock = std::chrono::steady_clock;

inline double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// A table cell: `decimals` after the point, "—" for NaN (no value).
inline std::string fmt(double x, int decimals = 1) {
  if (std::isnan(x)) return "—";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return buf;
}

inline double median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return std::isnan(x); }), v.end());
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

inline double quantileSorted(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return std::nan("");
  const double n = static_cast<double>(sorted.size());
  const auto rank = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(q * n)));
  return sorted[std::min(rank, sorted.size()) - 1];
}

inline std::string loadAverage() {
  std::string s = readFile("/proc/loadavg");
  return s.substr(0, s.find(' ', s.find(' ', s.find(' ') + 1) + 1));
}

// Rss and Pss of a live process, kB (nullopt if it is gone).
struct Memory {
  double rss_kb = 0, pss_kb = 0;
};
inline std::optional<Memory> memoryOf(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/smaps_rollup");
  if (!in) return std::nullopt;
  Memory m;
  bool rss = false, pss = false;
  for (std::string line; std::getline(in, line);) {
    std::istringstream ls(line);
    std::string key;
    double kb = 0;
    ls >> key >> kb;
    if (key == "Rss:") {
      m.rss_kb = kb;
      rss = true;
    } else if (key == "Pss:") {
      m.pss_kb = kb;
      pss = true;
    }
  }
  if (!rss || !pss) return std::nullopt;
  return m;
}

// utime + stime of a live process, seconds.
inline std::optional<double> cpuSecondsOf(pid_t pid) {
  const std::string stat = readFile("/proc/" + std::to_string(pid) + "/stat");
  const std::size_t close = stat.rfind(')');
  if (stat.empty() || close == std::string::npos) return std::nullopt;
  std::istringstream s(stat.substr(close + 2));
  std::vector<std::string> f;
  for (std::string x; s >> x;) f.push_back(x);
  if (f.size() < 13) return std::nullopt;  // fields 3.. of proc(5): utime is field 14, stime 15
  return (std::strtod(f[11].c_str(), nullptr) + std::strtod(f[12].c_str(), nullptr)) /
         static_cast<double>(::sysconf(_SC_CLK_TCK));
}

// Time on a CPU of a live process's threads, seconds, to the nanosecond (proc(5) schedstat), for spans too short for
// the clock ticks of cpuSecondsOf. Threads that ended are not counted.
inline std::optional<double> cpuSecondsFine(pid_t pid) {
  std::error_code ec;
  const std::filesystem::path tasks = "/proc/" + std::to_string(pid) + "/task";
  double ns = 0.0;
  bool any = false;
  for (const auto& t : std::filesystem::directory_iterator(tasks, ec)) {
    std::istringstream s(readFile((t.path() / "schedstat").string()));
    double on_cpu_ns = 0.0;
    if (s >> on_cpu_ns) {
      ns += on_cpu_ns;
      any = true;
    }
  }
  if (!any) return std::nullopt;
  return ns * 1e-9;
}

// The live children of `parent` whose command name (proc(5) comm, at most 15 characters) is `comm`.
inline std::vector<pid_t> childrenNamed(pid_t parent, const std::string& comm) {
  std::vector<pid_t> out;
  DIR* proc = ::opendir("/proc");
  if (proc == nullptr) return out;
  while (const dirent* e = ::readdir(proc)) {
    const char* name = e->d_name;
    if (*name < '0' || *name > '9') continue;
    const std::string stat = readFile(std::string("/proc/") + name + "/stat");
    const std::size_t open = stat.find('('), close = stat.rfind(')');
    if (open == std::string::npos || close == std::string::npos || close < open) continue;
    std::istringstream rest(stat.substr(close + 2));
    std::string state;
    long ppid = 0;
    rest >> state >> ppid;
    if (ppid == parent && stat.substr(open + 1, close - open - 1) == comm) {
      out.push_back(static_cast<pid_t>(std::atol(name)));
    }
  }
  ::closedir(proc);
  return out;
}

// How many live processes other than this one have `text` in their command line (arguments joined by spaces).
inline int processesMentioning(const std::string& text) {
  int count = 0;
  DIR* proc = ::opendir("/proc");
  if (proc == nullptr) return 0;
  while (const dirent* e = ::readdir(proc)) {
    const char* name = e->d_name;
    if (*name < '0' || *name > '9' || std::atol(name) == ::getpid()) continue;
    std::string cmdline = readFile(std::string("/proc/") + name + "/cmdline");
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    if (cmdline.find(text) != std::string::npos) ++count;
  }
  ::closedir(proc);
  return count;
}

}  // namespace swa::bench
