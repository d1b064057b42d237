// How many UAV processes one host runs, and what the loop costs against Fast DDS itself (issue #29). For each N of
// --sizes, in one run of this program, one after the other so that both see the same machine:
//   (1) the raw fan-out floor: N echo peers (bench_dds --echo N listener: a participant that answers each ping from
//       its listener, no SWA code), the transport, profiles and topic layout of the run (one ping / pong topic pair
//       per peer). A round writes one ping per peer in a row and waits for every pong, as the simulator writes a
//       step's IMU samples and waits for every command in lockstep; the median round;
//   (2) swa_launch of dropout_8 with uav_count = N in lockstep: discovery (launch to the simulator's "discovered"),
//       wall time per step and its ratio to (1), CPU per received sample in the agents and per UAV-step in the
//       simulator (from their own log lines: an agent's from its first IMU sample on, the simulator's whole run), PSS
//       per agent (the last sample of all of them, taken every 0.5 s while the run steps), the verdict, and whether
//       the time series equals swa_batch's byte for byte.
// Then SIGTERM to a launch of --stop-size UAVs (time until every process is gone), and realtime at 100 Hz for each N
// of --realtime-sizes: late + missing commands.
// The transport is swa_launch's own choice unless --transport: local up to 32 UAV processes, a discovery server
// beyond (launch_options.h). Each N runs on a DDS domain reserved among SWA's tests and benchmarks, and the next one
// too (past 118 participants the ports spill into it: swa/dds/participant_id.h). Prints Markdown tables; not a ctest.
//
// Usage: bench_scale [--sizes 8,16,32,64,100,128] [--duration S] [--realtime-sizes 8,16,32,48,64]
//                    [--realtime-duration S] [--rounds R] [--transport auto|local|discovery-server]
//                    [--stop-size N] [--out DIR]

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>

#include "launch_options.h"
#include "proc_stats.h"
#include "process_support.h"
#include "swa/app/cli.h"
#include "swa/app/number.h"
#include "swa/app/signals.h"
#include "swa/app/udp_port.h"
#include "swa/dds/options.h"
#include "swa/dds/participant.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/sample_queue.h"

// Fast DDS declares a global `namespace dds`: stay inside namespace swa so `dds::` is ours.
namespace swa::bench {
namespace {

using testing::Child;
using testing::jsonNumber;
namespace fs = std::filesystem;

const std::string kSource = SWA_SOURCE_DIR;
const std::string kScenario = kSource + "/deploy/scenarios/dropout_8.yaml";

struct Options {
  std::vector<int> sizes{8, 16, 32, 64, 100, 128};
  std::vector<int> realtime_sizes{8, 16, 32, 48, 64};
  double duration_s = 10.0;
  double realtime_duration_s = 20.0;
  int rounds = 300;
  std::string transport = "auto";
  std::string out = "/tmp/swa_bench_scale";
  int stop_size = 100;
  bool help = false;
};

// "8,16,32" into UAV counts in [1, 200]; an empty text is no size at all.
app::Cli::Read sizesInto(std::vector<int>& out, const std::string& option) {
  return [&out, option](const std::string& text, app::Problems& problems) {
    out.clear();
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
      const auto n = app::parseInteger(item, 1, 200);
      if (!n) {
        problems.push_back(option + " '" + text + "' is not a list of UAV counts in [1, 200]");
        out.clear();
        return;
      }
      out.push_back(static_cast<int>(*n));
    }
  };
}

app::Cli makeCli(Options& o) {
  app::Cli cli("bench_scale",
               "how many UAV processes one host runs, against the raw Fast DDS fan-out "
               "(BENCHMARKS.md).");
  cli.usage(
      "bench_scale [--sizes N,N,..] [--duration S] [--realtime-sizes N,N,..] [--realtime-duration S]\n"
      "                   [--rounds R] [--transport auto|local|discovery-server] [--stop-size N] [--out DIR]");
  cli.value("--sizes", "N,..", sizesInto(o.sizes, "--sizes"), "lockstep runs (default 8,16,32,64,100,128)");
  cli.value("--realtime-sizes", "N,..", sizesInto(o.realtime_sizes, "--realtime-sizes"),
            "realtime runs at 100 Hz (default 8,16,32,48,64; '' for none)");
  cli.real("--duration", "S", o.duration_s, 1.0, 600.0, "a duration in seconds", "simulated seconds per lockstep run");
  cli.real("--realtime-duration", "S", o.realtime_duration_s, 1.0, 600.0, "a duration in seconds",
           "simulated seconds per realtime run");
  cli.integer("--rounds", "R", o.rounds, 10, 100000, "a count", "fan-out rounds of the raw floor per N");
  const std::vector<std::string> transports{"auto", "local", "discovery-server"};
  cli.choice(
      "--transport", "T", transports, [&o, transports](std::size_t k) { o.transport = transports[k]; },
      "auto (default): swa_launch's choice, local up to 32 UAV processes, then a discovery server");
  cli.integer("--stop-size", "N", o.stop_size, 0, 200, "a UAV count",
              "SIGTERM to a launch of N UAVs 3 s after discovery: time until every process is gone (0: skip)");
  cli.path("--out", "DIR", o.out, "where the runs' files go (default /tmp/swa_bench_scale)");
  return cli;
}

// Two consecutive DDS domains reserved among SWA's tests and benchmarks (test_domain.h): the run's and the next,
// whose port range a run of more than 118 participants spills into.
int reserveDomainPair() {
  int first = 1 + static_cast<int>(::getpid() % 200);
  for (int attempt = 0; attempt < 232; ++attempt) {
    const int d = testing::reserveTestDomain(first);
    if (d < 0) break;
    if (d < 232 && testing::reserveTestDomain(d + 1) == d + 1) return d;
    first = d % 232 + 1;  // what was reserved on the way stays held until exit: harmless
  }
  throw std::runtime_error("no two consecutive free DDS domains among SWA's reservations");
}

std::string transportFor(const Options& o, int n) {
  if (o.transport != "auto") return o.transport;
  return n > launch::kMaxUavProcessesForSimpleDiscovery ? "discovery-server" : "local";
}

// A discovery server of this benchmark's own on a free port; SWA_DISCOVERY_SERVER names it for what follows.
class DiscoveryServer {
 public:
  explicit DiscoveryServer(const fs::path& log) {
    const std::optional<int> port = app::firstFreeUdpPort(11811, 100);
    if (!port) throw std::runtime_error("no free UDP port for a discovery server");
    server_ = std::make_unique<Child>(std::vector<std::string>{"/usr/bin/fast-discovery-server", "-i", "0", "-l",
                                                               "127.0.0.1", "-p", std::to_string(*port)},
                                      log);
    ::setenv("SWA_DISCOVERY_SERVER", ("127.0.0.1:" + std::to_string(*port)).c_str(), 1);
  }
  ~DiscoveryServer() {
    ::unsetenv("SWA_DISCOVERY_SERVER");
    server_->signal(SIGINT);  // on SIGTERM it would leave its /dev/shm files
    server_->stop(5.0);
  }
  DiscoveryServer(const DiscoveryServer&) = delete;
  DiscoveryServer& operator=(const DiscoveryServer&) = delete;

 private:
  std::unique_ptr<Child> server_;
};

// ---- (1) the raw fan-out floor ------------------------------------------------------------------------------------

struct FanOut {
  double discovery_s = NAN, round_p50_us = NAN, round_p99_us = NAN;
  // The floor of the CPU figures over the measured rounds: an echo peer's per ping answered, the pinger's per ping
  // sent and answer taken (what an agent and the simulator do per sample, with no SWA code).
  double echo_cpu_per_ping_us = NAN, ping_cpu_per_peer_round_us = NAN;
  int lost_rounds = 0;
  std::string error;
};

struct Pong {
  std::uint32_t peer = 0, seq = 0;
};

FanOut rawFanOut(const Options& o, int n, int domain, const fs::path& dir) {
  FanOut r;
  std::vector<std::unique_ptr<Child>> echoes;
  const std::string echo_binary = (fs::path(SWA_BENCH_DDS_BINARY)).string();
  for (int j = 0; j < n; ++j) {
    echoes.push_back(std::make_unique<Child>(
        std::vector<std::string>{echo_binary, "--echo", std::to_string(domain), "listener", std::to_string(j)},
        dir / ("echo_" + std::to_string(j) + ".log")));
  }
  dds::SampleQueue<Pong> queue;
  {
    dds::Participant p("swa_bench_scale_ping", domain, dds::resolveProfilesFile());
    std::vector<dds::Writer<msg::Imu>> pings;
    std::vector<dds::Reader<msg::VelocitySetpoint>> pongs;
    const auto t0 = Clock::now();
    for (int j = 0; j < n; ++j) {
      pings.push_back(p.writer<msg::ImuPubSubType>("swa/bench/ping" + std::to_string(j), dds::qos::kSensorWriter));
      pongs.push_back(p.reader<msg::VelocitySetpointPubSubType>(
          "swa/bench/pong" + std::to_string(j), dds::qos::kCommandReader, [&queue](msg::VelocitySetpoint&& m) {
            queue.push(Pong{m.uav_id(), m.answered_seq()});
          }));
    }
    const auto allMatched = [&] {
      for (std::size_t j = 0; j < pings.size(); ++j) {
        if (pings[j].matched() < 1 || pongs[j].matched() < 1) return false;
      }
      return true;
    };
    while (!allMatched() && secondsSince(t0) < 120.0 && !app::shutdownRequested()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (!allMatched()) {
      r.error = "echo peers not discovered in 120 s";
    } else {
      r.discovery_s = secondsSince(t0);
      constexpr int kWarmup = 20;
      std::vector<double> rounds_us;
      std::vector<Pong> batch;
      double echo_cpu0_s = 0.0, ping_cpu0_s = 0.0;
      for (int round = 1; round <= kWarmup + o.rounds && !app::shutdownRequested(); ++round) {
        if (round == kWarmup + 1) {
          for (const auto& e : echoes) echo_cpu0_s += cpuSecondsFine(e->pid()).value_or(NAN);
          ping_cpu0_s = cpuSecondsFine(::getpid()).value_or(NAN);
        }
        const auto start = Clock::now();
        for (int j = 0; j < n; ++j) {
          msg::Imu m;
          m.header().seq(static_cast<std::uint32_t>(round));
          m.header().stamp_ns(static_cast<std::int64_t>(round) * 10'000'000);
          m.uav_id(static_cast<std::uint32_t>(j));
          pings[static_cast<std::size_t>(j)].write(m);
        }
        int answered = 0;
        const auto deadline = start + std::chrono::seconds(2);
        while (answered < n && Clock::now() < deadline) {
          batch.clear();
          queue.drain(batch, std::chrono::milliseconds(50));
          for (const Pong& x : batch) answered += x.seq == static_cast<std::uint32_t>(round) ? 1 : 0;
        }
        if (answered < n) {
          ++r.lost_rounds;
          continue;
        }
        if (round > kWarmup)
          rounds_us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
      }
      const double sent = static_cast<double>(n) * static_cast<double>(o.rounds);
      r.ping_cpu_per_peer_round_us = 1e6 * (cpuSecondsFine(::getpid()).value_or(NAN) - ping_cpu0_s) / sent;
      double echo_cpu1_s = 0.0;
      for (const auto& e : echoes) echo_cpu1_s += cpuSecondsFine(e->pid()).value_or(NAN);
      r.echo_cpu_per_ping_us = 1e6 * (echo_cpu1_s - echo_cpu0_s) / sent;
      std::sort(rounds_us.begin(), rounds_us.end());
      r.round_p50_us = quantileSorted(rounds_us, 0.5);
      r.round_p99_us = quantileSorted(rounds_us, 0.99);
    }
  }
  for (auto& e : echoes) e->signal(SIGTERM);
  for (auto& e : echoes) e->stop(10.0);
  return r;
}

// ---- (2) a launch -------------------------------------------------------------------------------------------------

struct LaunchRun {
  int status = -1;
  double discovery_s = NAN, wall_per_step_us = NAN, late_missing = NAN;
  double agent_cpu_per_sample_us = NAN, sim_cpu_per_uav_step_us = NAN;
  double pss_median_mb = NAN, pss_max_mb = NAN;
  std::optional<bool> equals_batch;  // lockstep only
  std::string summary;
};

// Sum over the agents' logs of the CPU time they spent from their first IMU sample to their end (start-up and
// discovery excluded) and of the samples they received.
void agentCpu(const fs::path& logs, int n, double& cpu_s, double& samples) {
  static const std::regex kCounts(R"(after (\d+) IMU, (\d+) detection, (\d+) GNSS samples)");
  static const std::regex kBefore(R"(first IMU sample .*, ([0-9.]+) s of CPU time before it)");
  static const std::regex kTotal(R"(swa_agent \d+: ([0-9.]+) s of CPU time)");
  cpu_s = 0.0;
  samples = 0.0;
  for (int i = 0; i < n; ++i) {
    const std::string log = readFile(logs / ("agent_" + std::to_string(i) + ".log"));
    std::smatch counts, before, total;
    if (!std::regex_search(log, counts, kCounts) || !std::regex_search(log, before, kBefore) ||
        !std::regex_search(log, total, kTotal)) {
      continue;  // restarted or killed: not counted
    }
    samples += std::stod(counts[1]) + std::stod(counts[2]) + std::stod(counts[3]);
    cpu_s += std::stod(total[1]) - std::stod(before[1]);
  }
}

LaunchRun launchRun(const Options& o, int n, bool realtime, int domain, const fs::path& dir) {
  LaunchRun r;
  const double duration_s = realtime ? o.realtime_duration_s : o.duration_s;
  const std::vector<std::string> sets{"uav_count=" + std::to_string(n), "duration_s=" + std::to_string(duration_s),
                                      std::string("clock.mode=") + (realtime ? "realtime" : "lockstep")};
  std::vector<std::string> argv{SWA_LAUNCH_BINARY,
                                "--scenario",
                                kScenario,
                                "--out",
                                dir.string(),
                                "--domain",
                                std::to_string(domain),
                                "--timeout-s",
                                std::to_string(300.0 + 30.0 * duration_s)};
  for (const std::string& s : sets) argv.insert(argv.end(), {"--set", s});
  if (o.transport != "auto") argv.insert(argv.end(), {"--transport", o.transport});
  const auto t0 = Clock::now();
  Child launch(argv, dir.string() + ".log");
  std::optional<int> status;
  std::optional<Clock::time_point> discovered, sampled;
  while (!(status = launch.wait(0.05))) {
    if (!discovered && readFile(dir / "logs" / "sim.log").find("discovered in") != std::string::npos) {
      discovered = Clock::now();
      r.discovery_s = secondsSince(t0);
    }
    // Every 0.5 s while the run steps (a lockstep run of 8 UAVs lasts about a second): the last full sample counts.
    if (discovered && secondsSince(*discovered) > 0.2 && (!sampled || secondsSince(*sampled) > 0.5)) {
      sampled = Clock::now();
      std::vector<double> pss;
      for (const pid_t pid : childrenNamed(launch.pid(), "swa_agent")) {
        if (const auto m = memoryOf(pid)) pss.push_back(m->pss_kb / 1024.0);
      }
      if (static_cast<int>(pss.size()) == n) {
        r.pss_median_mb = median(pss);
        r.pss_max_mb = *std::max_element(pss.begin(), pss.end());
      }
    }
    if (app::shutdownRequested()) launch.signal(SIGTERM);
  }
  r.status = *status;
  r.summary = readFile(dir / "sim_summary.json");
  const double steps = jsonNumber(r.summary, "steps");
  r.wall_per_step_us = 1e6 * jsonNumber(r.summary, "wall_time_s") / steps;
  r.late_missing = jsonNumber(r.summary, "late_fraction") + jsonNumber(r.summary, "missing_fraction");
  double cpu_s = 0.0, samples = 0.0;
  agentCpu(dir / "logs", n, cpu_s, samples);
  if (samples > 0) r.agent_cpu_per_sample_us = 1e6 * cpu_s / samples;
  std::smatch m;
  const std::string sim_log = readFile(dir / "logs" / "sim.log");
  if (std::regex_search(sim_log, m, std::regex(R"(swa_sim: ([0-9.]+) s of CPU time)")) && steps > 0) {
    r.sim_cpu_per_uav_step_us = 1e6 * std::stod(m[1]) / (steps * n);
  }
  if (!realtime) {
    std::vector<std::string> batch{SWA_BATCH_BINARY, "--scenario", kScenario, "--out", (dir.string() + "_batch")};
    for (const std::string& s : sets) batch.insert(batch.end(), {"--set", s});
    Child b(batch, dir.string() + "_batch.log");
    if (b.wait(600.0) == 0) {
      r.equals_batch =
          readFile(dir / "timeseries.csv") == readFile(fs::path(dir.string() + "_batch") / "swa" / "seed_1.csv") &&
          !readFile(dir / "timeseries.csv").empty();
    }
  }
  return r;
}

// SIGTERM to a lockstep launch of o.stop_size UAVs 3 s after discovery: seconds until swa_launch has exited and no
// process of the run is left, and the run's verdict line.
double stopTime(const Options& o, int domain, const fs::path& dir, std::string& verdict) {
  std::vector<std::string> argv{SWA_LAUNCH_BINARY,
                                "--scenario",
                                kScenario,
                                "--out",
                                dir.string(),
                                "--domain",
                                std::to_string(domain),
                                "--set",
                                "uav_count=" + std::to_string(o.stop_size),
                                "--set",
                                "duration_s=3600",
                                "--timeout-s",
                                "600"};
  if (o.transport != "auto") argv.insert(argv.end(), {"--transport", o.transport});
  Child launch(argv, dir.string() + ".log");
  const auto t0 = Clock::now();
  std::optional<Clock::time_point> discovered;
  while (!launch.wait(0.05) && secondsSince(t0) < 300.0 && !app::shutdownRequested()) {
    if (!discovered && readFile(dir / "logs" / "sim.log").find("discovered in") != std::string::npos) {
      discovered = Clock::now();
    }
    if (discovered && secondsSince(*discovered) > 3.0) break;
  }
  const auto stopped = Clock::now();
  launch.signal(SIGTERM);
  launch.wait(300.0);
  while (processesMentioning(dir.string()) > 0 && secondsSince(stopped) < 300.0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const double seconds = secondsSince(stopped);
  const std::string log = readFile(dir.string() + ".log");
  const std::size_t last = log.rfind("swa_launch [");
  verdict = last == std::string::npos ? "no verdict line" : log.substr(last, log.find('\n', last) - last);
  return discovered ? seconds : NAN;
}

std::string verdictOf(int status) {
  return status == 0 ? "PASS" : status == 1 ? "FAIL" : status == 3 ? "INCOMPLETE" : "exit " + std::to_string(status);
}

int benchMain(const Options& o) {
  fs::create_directories(o.out);
  int failures = 0;
  std::printf("## bench_scale: %ld cores, load %s at start; lockstep %.0f s simulated per run, raw floor %d rounds\n\n",
              ::sysconf(_SC_NPROCESSORS_ONLN), loadAverage().c_str(), o.duration_s, o.rounds);
  std::printf(
      "| N | transport | discovery: launch / raw | wall per step | raw fan-out round p50 (p99) | ratio | "
      "agent CPU per received sample / raw echo's per ping (ratio) | sim CPU per UAV-step / raw pinger's per "
      "ping (ratio) | PSS per agent median / max | verdict | = swa_batch |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::fflush(stdout);
  for (const int n : o.sizes) {
    if (app::shutdownRequested()) break;
    const int domain = reserveDomainPair();
    testing::useOwnSwarm();
    const std::string transport = transportFor(o, n);
    ::setenv("SWA_TRANSPORT", transport.c_str(), 1);
    const fs::path dir = fs::path(o.out) / ("n" + std::to_string(n));
    fs::remove_all(dir);
    fs::create_directories(dir / "raw");
    FanOut raw;
    {
      std::unique_ptr<DiscoveryServer> server;
      if (transport == "discovery-server") server = std::make_unique<DiscoveryServer>(dir / "raw" / "server.log");
      raw = rawFanOut(o, n, domain, dir / "raw");
    }
    ::unsetenv("SWA_TRANSPORT");
    const LaunchRun run = launchRun(o, n, false, domain, dir / "lockstep");
    const double ratio = run.wall_per_step_us / raw.round_p50_us;
    failures += run.status != 0 || run.equals_batch != true || !raw.error.empty();
    const auto against = [](double swa_us, double raw_us) {
      return fmt(swa_us, 0) + " / " + fmt(raw_us, 0) + " us (" + fmt(swa_us / raw_us, 2) + ")";
    };
    std::printf("| %d | %s | %s s / %s s | %s us | %s us (%s us)%s | %s | %s | %s | %s / %s MB | %s | %s |\n", n,
                transport.c_str(), fmt(run.discovery_s, 2).c_str(), fmt(raw.discovery_s, 2).c_str(),
                fmt(run.wall_per_step_us, 0).c_str(), fmt(raw.round_p50_us, 0).c_str(),
                fmt(raw.round_p99_us, 0).c_str(),
                raw.error.empty() ? (raw.lost_rounds ? (", " + std::to_string(raw.lost_rounds) + " lost").c_str() : "")
                                  : (" " + raw.error).c_str(),
                fmt(ratio, 2).c_str(), against(run.agent_cpu_per_sample_us, raw.echo_cpu_per_ping_us).c_str(),
                against(run.sim_cpu_per_uav_step_us, raw.ping_cpu_per_peer_round_us).c_str(),
                fmt(run.pss_median_mb, 2).c_str(), fmt(run.pss_max_mb, 2).c_str(), verdictOf(run.status).c_str(),
                !run.equals_batch   ? "—"
                : *run.equals_batch ? "yes"
                                    : "NO");
    std::fflush(stdout);
  }
  if (o.stop_size > 0 && !app::shutdownRequested()) {
    std::string verdict;
    const double seconds = stopTime(o, reserveDomainPair(), fs::path(o.out) / "stop", verdict);
    std::printf("\nSIGTERM to a lockstep launch of %d UAVs 3 s after discovery: every process gone after %s s (%s)\n",
                o.stop_size, fmt(seconds, 1).c_str(), verdict.c_str());
  }
  if (!o.realtime_sizes.empty()) {
    std::printf("\n### Realtime at 100 Hz, %.0f s per N (late + missing < 1 %% passes)\n\n", o.realtime_duration_s);
    std::printf(
        "| N | transport | late + missing | loop latency p50 / p99 | agent CPU per received sample | passes |\n"
        "|---|---|---|---|---|---|\n");
    for (const int n : o.realtime_sizes) {
      if (app::shutdownRequested()) break;
      const int domain = reserveDomainPair();
      const fs::path dir = fs::path(o.out) / ("realtime_n" + std::to_string(n));
      fs::remove_all(dir);
      fs::create_directories(dir.parent_path());
      const LaunchRun run = launchRun(o, n, true, domain, dir);
      std::printf("| %d | %s | %s %% | %s / %s us | %s us | %s |\n", n, transportFor(o, n).c_str(),
                  fmt(100.0 * run.late_missing, 2).c_str(), fmt(jsonNumber(run.summary, "latency_p50_us"), 0).c_str(),
                  fmt(jsonNumber(run.summary, "latency_p99_us"), 0).c_str(),
                  fmt(run.agent_cpu_per_sample_us, 0).c_str(),
                  run.status == 0 && run.late_missing < 0.01 ? "yes" : "no");
      std::fflush(stdout);
    }
  }
  std::printf("\nload %s at the end\n", loadAverage().c_str());
  return failures == 0 ? 0 : 1;
}

}  // namespace
}  // namespace swa::bench

int main(int argc, char** argv) {
  try {
    const swa::bench::Options o = swa::app::parseOptions<swa::bench::Options>(
        std::vector<std::string>(argv + 1, argv + argc), swa::bench::makeCli);
    if (o.help) {
      std::fputs(swa::app::helpText(swa::bench::makeCli).c_str(), stdout);
      return 0;
    }
    swa::app::installShutdownHandlers();
    swa::app::acceptShutdownSignals();
    return swa::bench::benchMain(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_scale: %s\n", e.what());
    return 2;
  }
}
