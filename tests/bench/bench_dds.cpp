// The swarm over Fast DDS, measured (issue #4). One invocation runs, in this order:
//   (a) raw Fast DDS ping-pong: this program re-executes itself as an echo peer; ping = swa::msg::Imu with the
//       sensor profiles, pong = swa::msg::VelocitySetpoint with the command profiles (the loop's message sizes,
//       QoS and transports), paced at 100 Hz; round trip p50 / p99. Twice: echo from the reader's listener (the raw
//       floor, the reference of the targets) and echo through a worker thread as swa_agent does (informative);
//   (b) loop latency: swa_sim in realtime + 8 swa_agent processes (dropout_8), latency from the simulator's
//       --summary-out (IMU published -> its cmd_vel received), and its ratio to (a); then with 1, 2, 4 agents;
//   (c) lockstep speed: simulated seconds per wall second for N = 4, 8, 16, 32;
//   (d) scale: realtime at 100 Hz for N = 8, 16, 24, 32 (then 40, 48 if 32 passes): late + missing commands;
//   (e) per-agent RSS / PSS from /proc/<pid>/smaps_rollup while the runs of (b) and (d) are in progress.
// Each run uses a DDS domain reserved among SWA's tests and a swarm of its own, every child is reaped and every
// /dev/shm file a killed process leaves is removed. Prints Markdown tables. Not a ctest: takes minutes and needs a
// quiet machine.
//
// Usage: bench_dds [--quick] [--only latency|lockstep|scale|pingpong] [--duration S] [--reps R] [--pings N]
//                  [--keep DIR]
//        bench_dds --echo DOMAIN listener|thread PEER (internal: a ping-pong echo peer)

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>

#include "proc_stats.h"
#include "process_support.h"
#include "swa/app/cli.h"
#include "swa/app/signals.h"
#include "swa/dds/options.h"
#include "swa/dds/participant.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/sample_queue.h"

// Fast DDS declares a global `namespace dds`: stay inside namespace swa so `dds::` is ours.
namespace swa::bench {
namespace {

using testing::Child;
using testing::jsonNumber;
using testing::readFile;
using testing::ShmJanitor;
namespace fs = std::filesystem;

const std::string kSource = SWA_SOURCE_DIR;
// One ping / pong topic pair per echo peer, as each UAV has its own imu / cmd_vel topics.
std::string pingTopic(int peer) { return "swa/bench/ping" + std::to_string(peer); }
std::string pongTopic(int peer) { return "swa/bench/pong" + std::to_string(peer); }
constexpr auto kPingPeriod = std::chrono::milliseconds(10);  // 100 Hz, as the IMU

// ---- options ----------------------------------------------------------------------------------------------------

struct Options {
  bool quick = false;
  std::string only;          // "", latency, lockstep, scale
  double duration_s = 30.0;  // realtime swarm runs of (b); (d) uses 2/3 of it, (c) 2x
  int reps = 1;              // repetitions of (a)+(b) and of each (c) run; medians reported
  int pings = 3000;          // round trips per ping-pong
  std::string keep;          // keep logs and summaries here
  bool help = false;
};

app::Cli makeCli(Options& o) {
  app::Cli cli("bench_dds", "the SWA swarm over Fast DDS, measured (see BENCHMARKS.md).");
  cli.usage(R"(bench_dds [--quick] [--only latency|lockstep|scale|pingpong|security] [--duration S] [--reps R]
                 [--pings N] [--keep DIR])");
  cli.details(
      R"(  --only latency   (a) raw ping-pong (Imu -> VelocitySetpoint, the loop's profiles) and (b) the realtime loop
                   with 8 agents, plus the loop with 1, 2, 4 agents (informative: how it grows with N)
  --only pingpong  (a) alone
  --only lockstep  (c) lockstep speed N = 4, 8, 16, 32
  --only scale     (d) realtime scale N = 8 .. 48 and (e) per-agent RSS / PSS
  --only security  (f) the N = 8 realtime loop with DDS Security off and on (credentials made by
                   deploy/security/make-credentials.sh), alternating, R repetitions each
  Without --only: all of them but (f). SWA_DDS_PROFILES (as for swa_sim / swa_agent) applies to every process.)");
  cli.flag("--quick", o.quick, "shorter runs: --duration 10 and --pings 500 unless given");
  const std::vector<std::string> parts{"latency", "lockstep", "scale", "pingpong", "security"};
  cli.choice(
      "--only", "PART", parts, [&o, parts](std::size_t k) { o.only = parts[k]; }, "run only this part (above)");
  cli.real("--duration", "S", o.duration_s, 2.0, 3600.0, "a duration in seconds",
           "wall seconds of the realtime run of (b); (d) runs 2/3 of it, (c) 2x of simulated time");
  cli.integer("--reps", "R", o.reps, 1, 100, "a count", "repeat (a)+(b) and each (c) run R times, report medians");
  cli.integer("--pings", "N", o.pings, 10, 1'000'000, "a count", "round trips per ping-pong");
  cli.path("--keep", "DIR", o.keep, "keep every log and summary in DIR (default: a temporary directory, removed)");
  return cli;
}

Options parseOptions(int argc, char** argv) {
  return app::parseOptions<Options>(std::vector<std::string>(argv + 1, argv + argc), makeCli,
                                    [](Options& o, const app::Cli& cli, app::Problems&) {
                                      if (!o.quick) return;
                                      if (!cli.given("--duration")) o.duration_s = 10.0;
                                      if (!cli.given("--pings")) o.pings = 500;
                                    });
}

// ---- small helpers ----------------------------------------------------------------------------------------------

std::string selfPath() {
  char buf[4096];
  const ssize_t n = ::readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) throw std::runtime_error("cannot read /proc/self/exe");
  return std::string(buf, static_cast<std::size_t>(n));
}

// A domain and a swarm of this run's own: reserved among SWA's tests and benchmarks on this host (test_domain.h),
// a different one for every run, and a DDS partition of its own (useOwnSwarm) for every participant of the run,
// its children included, so another DDS user on the same domain neither disturbs the run nor is disturbed by it.
int nextDomain() {
  static int counter = 0;
  const int domain = testing::testDomain(7 * counter++);
  testing::useOwnSwarm();
  return domain;
}

// ---- (a) ping-pong ----------------------------------------------------------------------------------------------

struct Pong {
  std::uint32_t peer = 0;
  std::uint32_t seq = 0;
  Clock::time_point received;
};

struct PingResult {
  int count = 0, lost = 0;
  double p50_us = NAN, p99_us = NAN, max_us = NAN, mean_us = NAN;
};

// The echo peer: answers every ping with a pong echoing its seq and stamp, from the listener (raw) or through a
// queue and this thread (as swa_agent: listener -> queue -> worker -> write).
int echoMain(int domain, const std::string& mode, int index) {
  app::installShutdownHandlers();
  dds::SampleQueue<msg::Imu> queue;
  const bool in_listener = mode == "listener";
  auto participant = std::make_unique<dds::Participant>("swa_bench_echo", domain, dds::resolveProfilesFile());
  dds::Writer<msg::VelocitySetpoint> pong =
      participant->writer<msg::VelocitySetpointPubSubType>(pongTopic(index), dds::qos::kCommandWriter);
  const auto answer = [&pong](const msg::Imu& ping) {
    msg::VelocitySetpoint out;
    out.header().stamp_ns(ping.header().stamp_ns());
    out.header().seq(ping.header().seq());
    out.uav_id(ping.uav_id());
    out.answered_stamp_ns(ping.header().stamp_ns());
    out.answered_seq(ping.header().seq());
    pong.write(out);
  };
  participant->reader<msg::ImuPubSubType>(pingTopic(index), dds::qos::kSensorReader, [&](msg::Imu&& m) {
    if (in_listener) {
      answer(m);
    } else {
      queue.push(std::move(m));
    }
  });
  app::acceptShutdownSignals();
  std::vector<msg::Imu> batch;
  while (!app::shutdownRequested()) {
    batch.clear();
    queue.drain(batch, std::chrono::milliseconds(100));
    for (const msg::Imu& m : batch) answer(m);
  }
  participant.reset();
  return 0;
}

// `peers` echo processes answer at once, each on its own topic pair: every 10 ms the pinger writes one ping per
// peer in a row, as swa_sim writes one IMU sample per UAV. Round trip = just before a ping's write() -> its pong in
// the listener, so with several peers it includes the queueing of peers that share the 2 vCPUs, not the pinger's
// own writes to the other peers.
PingResult pingPong(const Options& opt, const fs::path& dir, const std::string& mode, int peers) {
  ShmJanitor janitor;
  const int domain = nextDomain();
  std::vector<std::unique_ptr<Child>> echoes;
  for (int j = 0; j < peers; ++j) {
    echoes.push_back(std::make_unique<Child>(
        std::vector<std::string>{selfPath(), "--echo", std::to_string(domain), mode, std::to_string(j)},
        dir / ("echo_" + mode + "_" + std::to_string(peers) + "_" + std::to_string(j) + ".log")));
  }
  dds::SampleQueue<Pong> queue;
  PingResult r;
  {
    dds::Participant p("swa_bench_ping", domain, dds::resolveProfilesFile());
    std::vector<dds::Writer<msg::Imu>> pings;
    std::vector<dds::Reader<msg::VelocitySetpoint>> pongs;
    for (int j = 0; j < peers; ++j) {
      pings.push_back(p.writer<msg::ImuPubSubType>(pingTopic(j), dds::qos::kSensorWriter));
      pongs.push_back(p.reader<msg::VelocitySetpointPubSubType>(
          pongTopic(j), dds::qos::kCommandReader, [&queue](msg::VelocitySetpoint&& m) {
            queue.push(Pong{m.uav_id(), m.answered_seq(), Clock::now()});
          }));
    }
    app::acceptShutdownSignals();
    const auto allMatched = [&] {
      for (int j = 0; j < peers; ++j) {
        if (pings[static_cast<std::size_t>(j)].matched() < 1 || pongs[static_cast<std::size_t>(j)].matched() < 1) {
          return false;
        }
      }
      return true;
    };
    const auto t_disc = Clock::now();
    while (!allMatched() && secondsSince(t_disc) < 30.0 && !app::shutdownRequested()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (!allMatched()) throw std::runtime_error("ping-pong: echo peers not discovered");

    constexpr int kWarmup = 100;
    const int total = kWarmup + opt.pings;
    const auto at = [total](std::uint32_t peer, std::uint32_t seq) {
      return static_cast<std::size_t>(peer) * (static_cast<std::size_t>(total) + 1) + seq;
    };
    const auto cells = static_cast<std::size_t>(peers) * (static_cast<std::size_t>(total) + 1);
    std::vector<Clock::time_point> sent(cells);
    std::vector<double> rtt_us(cells, NAN);
    std::vector<Pong> batch;
    const auto collect = [&](Clock::time_point until) {
      do {
        batch.clear();
        const auto now = Clock::now();
        queue.drain(batch, until > now ? until - now : Clock::duration::zero());
        for (const Pong& x : batch) {
          if (x.peer >= static_cast<std::uint32_t>(peers) || x.seq < 1 || x.seq > static_cast<std::uint32_t>(total)) {
            continue;
          }
          double& cell = rtt_us[at(x.peer, x.seq)];
          if (std::isnan(cell))
            cell = std::chrono::duration<double, std::micro>(x.received - sent[at(x.peer, x.seq)]).count();
        }
      } while (Clock::now() < until && !app::shutdownRequested());
    };
    const auto t0 = Clock::now();
    for (int i = 1; i <= total && !app::shutdownRequested(); ++i) {
      for (int j = 0; j < peers; ++j) {
        msg::Imu m;
        m.header().seq(static_cast<std::uint32_t>(i));
        m.header().stamp_ns(static_cast<std::int64_t>(i) * 10'000'000);
        m.uav_id(static_cast<std::uint32_t>(j));
        m.roll_rad(0.01 * i);
        m.pitch_rad(-0.01 * i);
        m.heading_rad(1.0);
        sent[at(static_cast<std::uint32_t>(j), static_cast<std::uint32_t>(i))] = Clock::now();
        pings[static_cast<std::size_t>(j)].write(m);
      }
      collect(t0 + i * kPingPeriod);
    }
    collect(Clock::now() + std::chrono::milliseconds(200));
    std::vector<double> v;
    for (int j = 0; j < peers; ++j) {
      for (int i = kWarmup + 1; i <= total; ++i) {
        const double x = rtt_us[at(static_cast<std::uint32_t>(j), static_cast<std::uint32_t>(i))];
        if (std::isnan(x)) {
          ++r.lost;
        } else {
          v.push_back(x);
        }
      }
    }
    std::sort(v.begin(), v.end());
    r.count = static_cast<int>(v.size());
    r.p50_us = quantileSorted(v, 0.5);
    r.p99_us = quantileSorted(v, 0.99);
    r.max_us = v.empty() ? NAN : v.back();
    double sum = 0;
    for (double x : v) sum += x;
    r.mean_us = v.empty() ? NAN : sum / static_cast<double>(v.size());
  }
  for (auto& e : echoes) e->stop(10.0);
  return r;
}

// ---- (b)-(e) swarm runs -----------------------------------------------------------------------------------------

struct SwarmSpec {
  std::string scenario;  // file under deploy/scenarios/
  int n = 8;
  bool realtime = true;
  double duration_s = 30.0;      // simulated
  std::string tag;               // names the run's files
  std::vector<std::string> env;  // extra environment of the simulator and the agents
};

struct SwarmResult {
  bool ok = false;
  std::string summary;
  double get(const std::string& key) const { return jsonNumber(summary, key); }
  double rss_median_mb = NAN, pss_median_mb = NAN, pss_max_mb = NAN;
  double sim_cpu_pct = NAN, agents_cpu_pct = NAN;  // over the measured window, % of one core
  std::string error;
};

SwarmResult runSwarm(const SwarmSpec& spec, const fs::path& dir) {
  ShmJanitor janitor;  // first: sees /dev/shm before anything of ours exists
  SwarmResult res;
  const int domain = nextDomain();
  const fs::path base = dir / spec.tag;
  fs::create_directories(base);
  std::vector<std::string> sim_args = {SWA_SIM_BINARY,
                                       "--scenario",
                                       kSource + "/deploy/scenarios/" + spec.scenario,
                                       "--set",
                                       "uav_count=" + std::to_string(spec.n),
                                       "--set",
                                       "duration_s=" + std::to_string(spec.duration_s)};
  if (spec.realtime) sim_args.insert(sim_args.end(), {"--set", "clock.mode=realtime"});
  {
    std::vector<std::string> exp = sim_args;
    exp.insert(exp.end(), {"--export-agent-config", (base / "agent.yaml").string()});
    Child exporter(exp, base / "export.log");
    if (exporter.wait(30.0) != 0) {
      res.error = "export failed: " + readFile(base / "export.log");
      return res;
    }
  }
  std::vector<std::unique_ptr<Child>> agents;
  for (int i = 0; i < spec.n; ++i) {
    agents.push_back(std::make_unique<Child>(
        std::vector<std::string>{SWA_AGENT_BINARY, "--id", std::to_string(i), "--config",
                                 (base / "agent.yaml").string(), "--domain", std::to_string(domain)},
        base / ("agent" + std::to_string(i) + ".log"), spec.env));
  }
  sim_args.insert(sim_args.end(), {"--domain", std::to_string(domain), "--summary-out",
                                   (base / "summary.json").string(), "--startup-timeout-s", "120"});
  Child sim(sim_args, base / "sim.log", spec.env);

  // Wait for the first step (the simulator logs the end of discovery), then sample CPU and memory at 20 % and 90 %
  // of a realtime run.
  const auto t0 = Clock::now();
  std::optional<Clock::time_point> stepping;
  std::optional<int> status;
  struct Sample {
    double sim_cpu = NAN;
    std::vector<double> agent_cpu;
    Clock::time_point at;
  };
  std::optional<Sample> first;
  std::vector<Memory> memory;
  const auto sampleCpu = [&] {
    Sample s;
    s.at = Clock::now();
    s.sim_cpu = cpuSecondsOf(sim.pid()).value_or(NAN);
    for (auto& a : agents) s.agent_cpu.push_back(cpuSecondsOf(a->pid()).value_or(NAN));
    return s;
  };
  const double bound_s = 180.0 + (spec.realtime ? spec.duration_s : 20.0 * spec.duration_s);
  while (!(status = sim.wait(0.05)) && secondsSince(t0) < bound_s && !app::shutdownRequested()) {
    if (!stepping) {
      if (readFile(base / "sim.log").find("discovered in") != std::string::npos) stepping = Clock::now();
      continue;
    }
    if (!spec.realtime) continue;
    const double t = std::chrono::duration<double>(Clock::now() - *stepping).count();
    if (!first && t >= 0.2 * spec.duration_s) first = sampleCpu();
    if (first && memory.empty() && t >= 0.9 * spec.duration_s) {
      const Sample second = sampleCpu();
      const double wall = std::chrono::duration<double>(second.at - first->at).count();
      res.sim_cpu_pct = 100.0 * (second.sim_cpu - first->sim_cpu) / wall;
      double agents_cpu = 0.0;
      for (std::size_t k = 0; k < agents.size(); ++k) agents_cpu += second.agent_cpu[k] - first->agent_cpu[k];
      res.agents_cpu_pct = 100.0 * agents_cpu / wall;
      for (auto& a : agents) {
        if (auto m = memoryOf(a->pid())) memory.push_back(*m);
      }
    }
  }
  if (!status) {
    res.error = "swa_sim did not finish in time (killed)";
    sim.stop(5.0);
  } else if (*status != 0) {
    res.error = "swa_sim exited with " + std::to_string(*status) + ": " + readFile(base / "sim.log");
  }
  for (auto& a : agents) a->signal(SIGTERM);
  for (auto& a : agents) a->stop(15.0);
  res.summary = readFile(base / "summary.json");
  res.ok = res.error.empty() && res.get("completed") == 1.0;
  if (res.ok == false && res.error.empty()) res.error = "run not completed";
  if (!memory.empty()) {
    std::vector<double> rss, pss;
    for (const Memory& m : memory) rss.push_back(m.rss_kb / 1024.0), pss.push_back(m.pss_kb / 1024.0);
    res.rss_median_mb = median(rss);
    res.pss_median_mb = median(pss);
    res.pss_max_mb = *std::max_element(pss.begin(), pss.end());
  }
  return res;
}

std::string scenarioFor(int n) {
  if (n == 4) return "dropout_4.yaml";
  if (n == 16) return "swarm_16.yaml";
  return "dropout_8.yaml";  // every other N: the same swarm (lattice at 10 m spacing, k = 3, r = 10 m) with N UAVs
}

// (a) + (b): the loop against the raw ping-pong, medians over the repetitions; then the loop with fewer agents.
int latencySection(const Options& opt, const fs::path& dir) {
  int failures = 0;
  std::vector<double> raw50, raw99, thr50, thr99, fan50, fan99, fanthr50, fanthr99, loop50, loop99, loopmax, late,
      missing, rss, pss;
  constexpr int kFanOut = 8;  // the loop's N
  for (int rep = 0; rep < opt.reps && !app::shutdownRequested(); ++rep) {
    const PingResult raw = pingPong(opt, dir, "listener", 1);
    const PingResult thr = pingPong(opt, dir, "thread", 1);
    const PingResult fan = pingPong(opt, dir, "listener", kFanOut);
    const PingResult fanthr = pingPong(opt, dir, "thread", kFanOut);
    std::printf(
        "rep %d ping-pong (%d round trips at 100 Hz): 1 peer, echo in listener p50 %.1f us p99 %.1f us max "
        "%.1f us (%d lost); 1 peer via worker thread p50 %.1f us p99 %.1f us (%d lost); %d peers in listener "
        "p50 %.1f us p99 %.1f us max %.1f us (%d lost); %d peers via worker thread p50 %.1f us p99 %.1f us "
        "(%d lost)\n",
        rep + 1, opt.pings, raw.p50_us, raw.p99_us, raw.max_us, raw.lost, thr.p50_us, thr.p99_us, thr.lost, kFanOut,
        fan.p50_us, fan.p99_us, fan.max_us, fan.lost, kFanOut, fanthr.p50_us, fanthr.p99_us, fanthr.lost);
    std::fflush(stdout);
    raw50.push_back(raw.p50_us);
    raw99.push_back(raw.p99_us);
    thr50.push_back(thr.p50_us);
    thr99.push_back(thr.p99_us);
    fan50.push_back(fan.p50_us);
    fan99.push_back(fan.p99_us);
    fanthr50.push_back(fanthr.p50_us);
    fanthr99.push_back(fanthr.p99_us);
    if (opt.only == "pingpong") continue;
    const SwarmSpec spec{"dropout_8.yaml", 8, true, opt.duration_s, "latency_rt8_rep" + std::to_string(rep + 1), {}};
    const SwarmResult s = runSwarm(spec, dir);
    if (!s.ok) {
      ++failures;
      std::printf("rep %d loop N = 8 realtime FAILED: %s\n", rep + 1, s.error.c_str());
      continue;
    }
    std::printf(
        "rep %d loop N = 8 realtime %.0f s: %.0f commands, p50 %.1f us p99 %.1f us max %.1f us, late %.0f, "
        "missing %.0f; agent RSS %.1f MB PSS %.1f MB (medians)\n",
        rep + 1, opt.duration_s, s.get("latency_commands_answered"), s.get("latency_p50_us"), s.get("latency_p99_us"),
        s.get("latency_max_us"), s.get("late_commands"), s.get("missing_answers"), s.rss_median_mb, s.pss_median_mb);
    std::fflush(stdout);
    loop50.push_back(s.get("latency_p50_us"));
    loop99.push_back(s.get("latency_p99_us"));
    loopmax.push_back(s.get("latency_max_us"));
    late.push_back(s.get("late_fraction"));
    missing.push_back(s.get("missing_fraction"));
    rss.push_back(s.rss_median_mb);
    pss.push_back(s.pss_median_mb);
  }
  const double r50 = median(raw50), r99 = median(raw99), l50 = median(loop50), l99 = median(loop99);
  std::printf("\n### Loop latency (medians of %d repetition(s))\n\n", opt.reps);
  std::printf("| measurement | p50 | p99 | target |\n|---|---|---|---|\n");
  std::printf(
      "| (a) raw ping-pong, echo in the listener (Imu -> VelocitySetpoint, %d round trips at 100 Hz) | %s us "
      "| %s us | reference |\n",
      opt.pings, fmt(r50).c_str(), fmt(r99).c_str());
  std::printf("| (a') ping-pong, echo through a worker thread as in swa_agent (informative) | %s us | %s us | — |\n",
              fmt(median(thr50)).c_str(), fmt(median(thr99)).c_str());
  const double f50 = median(fan50), f99 = median(fan99);
  std::printf(
      "| (a8) raw ping-pong with %d echo peers at once, echo in the listener (the raw floor at the loop's N) "
      "| %s us | %s us | reference at N = %d |\n",
      kFanOut, fmt(f50).c_str(), fmt(f99).c_str(), kFanOut);
  std::printf("| (a8') %d echo peers at once, echo through a worker thread (informative) | %s us | %s us | — |\n",
              kFanOut, fmt(median(fanthr50)).c_str(), fmt(median(fanthr99)).c_str());
  if (opt.only != "pingpong") {
    std::printf(
        "| (b) loop: IMU published by swa_sim -> its cmd_vel received, N = 8 realtime, %.0f s | %s us | %s us "
        "| |\n",
        opt.duration_s, fmt(l50).c_str(), fmt(l99).c_str());
    std::printf("| (b) / (a) | %s x | %s x | p50 <= 1.3 x, p99 <= 1.5 x |\n", fmt(l50 / r50, 2).c_str(),
                fmt(l99 / r99, 2).c_str());
    std::printf("| (a8) / (a): the fan-out alone, no agent code | %s x | %s x | — |\n", fmt(f50 / r50, 2).c_str(),
                fmt(f99 / r99, 2).c_str());
    std::printf(
        "| (b) / (a8): what the agent and simulator add at the same N | %s x | %s x | p50 <= 1.3 x, p99 <= "
        "1.5 x |\n",
        fmt(l50 / f50, 2).c_str(), fmt(l99 / f99, 2).c_str());
    std::printf(
        "\nloop N = 8: max %s us, late %s %%, missing %s %%; per-agent RSS %s MB, PSS %s MB (median over "
        "agents)\n",
        fmt(median(loopmax)).c_str(), fmt(100.0 * median(late), 3).c_str(), fmt(100.0 * median(missing), 3).c_str(),
        fmt(median(rss)).c_str(), fmt(median(pss), 2).c_str());
  }
  std::fflush(stdout);
  if (opt.only == "pingpong") return failures;

  // How the loop grows with the number of agents answering at the same instant (informative).
  const double sweep_s = std::max(5.0, opt.duration_s / 2.0);
  std::printf("\n| agents N (realtime, %.0f s each) | loop p50 | loop p99 | p50 / raw p50 |\n|---|---|---|---|\n",
              sweep_s);
  for (const int n : {1, 2, 4}) {
    if (app::shutdownRequested()) break;
    const SwarmSpec spec{"dropout_8.yaml", n, true, sweep_s, "latency_sweep_n" + std::to_string(n), {}};
    const SwarmResult s = runSwarm(spec, dir);
    if (!s.ok) {
      ++failures;
      std::printf("| %d | FAILED: %s | | |\n", n, s.error.c_str());
      continue;
    }
    std::printf("| %d | %s us | %s us | %s |\n", n, fmt(s.get("latency_p50_us")).c_str(),
                fmt(s.get("latency_p99_us")).c_str(), fmt(s.get("latency_p50_us") / r50, 2).c_str());
    std::fflush(stdout);
  }
  std::printf("| 8 | %s us | %s us | %s |\n", fmt(l50).c_str(), fmt(l99).c_str(), fmt(l50 / r50, 2).c_str());
  return failures;
}

// (c): simulated seconds per wall second in lockstep.
int lockstepSection(const Options& opt, const fs::path& dir) {
  int failures = 0;
  const double sim_s = 2.0 * opt.duration_s;
  std::printf("\n### Lockstep speed (%.0f s simulated per run, median of %d)\n\n", sim_s, opt.reps);
  std::printf(
      "| N | scenario | sim s / wall s (each run) | wall s per run | loop latency p50 / p99 | target |\n"
      "|---|---|---|---|---|---|\n");
  std::fflush(stdout);
  for (const int n : {4, 8, 16, 32}) {
    std::vector<double> speed, wall, p50, p99;
    for (int rep = 0; rep < opt.reps && !app::shutdownRequested(); ++rep) {
      const SwarmSpec spec{
          scenarioFor(n), n, false, sim_s, "lockstep_n" + std::to_string(n) + "_rep" + std::to_string(rep + 1), {}};
      const SwarmResult s = runSwarm(spec, dir);
      if (!s.ok || s.get("agent_dead_events") != 0.0) {
        ++failures;
        std::printf("| %d | lockstep run FAILED: %s (dead events %.0f) | | | | |\n", n, s.error.c_str(),
                    s.get("agent_dead_events"));
        continue;
      }
      speed.push_back(s.get("sim_time_s") / s.get("wall_time_s"));
      wall.push_back(s.get("wall_time_s"));
      p50.push_back(s.get("latency_p50_us"));
      p99.push_back(s.get("latency_p99_us"));
    }
    std::string each;
    for (const double x : speed) each += (each.empty() ? "" : ", ") + fmt(x);
    std::printf("| %d | %s | %sx (%s) | %s | %s / %s us | %s |\n", n, scenarioFor(n).c_str(),
                fmt(median(speed)).c_str(), each.c_str(), fmt(median(wall), 2).c_str(), fmt(median(p50)).c_str(),
                fmt(median(p99)).c_str(), n == 8 ? ">= 20x" : "—");
    std::fflush(stdout);
  }
  return failures;
}

// (d) + (e): realtime at 100 Hz for growing N; a run passes with < 1 % late or missing commands and no dead agent.
int scaleSection(const Options& opt, const fs::path& dir) {
  int failures = 0;
  const double run_s = std::max(5.0, opt.duration_s * 2.0 / 3.0);
  std::printf("\n### Scale: realtime at 100 Hz, %.0f s per N (late + missing < 1 %% passes)\n\n", run_s);
  std::printf(
      "| N | judged commands | late | missing | late + missing | latency p50 / p99 / max | sim step lag "
      "p99 / max | CPU sim / all agents (%% of one core) | per-agent RSS / PSS (median) | passes |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n");
  std::fflush(stdout);
  int largest = 0;
  for (const int n : {8, 16, 24, 32, 40, 48}) {
    if (app::shutdownRequested() || largest != n - 8) break;  // stop at the first failure
    if (n > 32 && largest < 32) break;                        // 40 and 48 only if 32 passes
    const SwarmSpec spec{scenarioFor(n), n, true, run_s, "scale_n" + std::to_string(n), {}};
    const SwarmResult s = runSwarm(spec, dir);
    if (!s.ok) {
      ++failures;
      std::printf("| %d | run FAILED: %s | | | | | | | | no |\n", n, s.error.c_str());
      break;
    }
    const double bad = s.get("late_fraction") + s.get("missing_fraction");
    const bool pass = bad < 0.01 && s.get("agent_dead_events") == 0.0;
    if (pass) largest = n;
    std::printf(
        "| %d | %.0f | %.0f (%s %%) | %.0f | %s %% | %s / %s / %s us | %s / %s us | %s / %s | %s / %s MB | "
        "%s |\n",
        n, s.get("latency_commands_judged"), s.get("late_commands"), fmt(100.0 * s.get("late_fraction"), 2).c_str(),
        s.get("missing_answers"), fmt(100.0 * bad, 2).c_str(), fmt(s.get("latency_p50_us")).c_str(),
        fmt(s.get("latency_p99_us")).c_str(), fmt(s.get("latency_max_us"), 0).c_str(),
        fmt(s.get("step_lag_p99_us")).c_str(), fmt(s.get("step_lag_max_us"), 0).c_str(), fmt(s.sim_cpu_pct, 0).c_str(),
        fmt(s.agents_cpu_pct, 0).c_str(), fmt(s.rss_median_mb).c_str(), fmt(s.pss_median_mb, 2).c_str(),
        pass ? "yes" : "no");
    std::fflush(stdout);
  }
  std::printf("\nlargest N realtime at 100 Hz with < 1 %% late or missing commands: %d (target >= 32)\n", largest);
  return failures;
}

// (f) The same N = 8 realtime loop with DDS Security off and on (authentication, access control, AES-GCM on data
// and metadata), interleaved so that both see the same machine load.
int securitySection(const Options& opt, const fs::path& dir) {
  const fs::path creds = dir / "creds";
  {
    Child make({"/bin/bash", kSource + "/deploy/security/make-credentials.sh", creds.string(), "8"},
               dir / "make-credentials.log");
    if (make.wait(120.0) != 0) {
      std::printf("security: make-credentials.sh failed: %s\n", readFile(dir / "make-credentials.log").c_str());
      return 1;
    }
  }
  int failures = 0;
  std::vector<double> off50, off99, on50, on99, late_on;
  for (int rep = 0; rep < opt.reps && !app::shutdownRequested(); ++rep) {
    for (const bool secure : {rep % 2 == 1, rep % 2 == 0}) {
      SwarmSpec spec{"dropout_8.yaml",
                     8,
                     true,
                     opt.duration_s,
                     std::string(secure ? "secure" : "plain") + "_rep" + std::to_string(rep + 1),
                     {}};
      if (secure) spec.env = {"SWA_SECURITY_DIR=" + creds.string()};
      const SwarmResult s = runSwarm(spec, dir);
      if (!s.ok) {
        ++failures;
        std::printf("rep %d security %s FAILED: %s\n", rep + 1, secure ? "on" : "off", s.error.c_str());
        continue;
      }
      std::printf(
          "rep %d loop N = 8 realtime, security %s: p50 %.1f us p99 %.1f us max %.1f us, late %.0f, "
          "missing %.0f; agent PSS %.1f MB\n",
          rep + 1, secure ? "on " : "off", s.get("latency_p50_us"), s.get("latency_p99_us"), s.get("latency_max_us"),
          s.get("late_commands"), s.get("missing_answers"), s.pss_median_mb);
      std::fflush(stdout);
      (secure ? on50 : off50).push_back(s.get("latency_p50_us"));
      (secure ? on99 : off99).push_back(s.get("latency_p99_us"));
      if (secure) late_on.push_back(s.get("late_fraction"));
    }
  }
  std::printf("\n### Loop latency with DDS Security (N = 8 realtime, %.0f s, medians of %d)\n\n", opt.duration_s,
              opt.reps);
  std::printf("| security | p50 | p99 |\n|---|---|---|\n| off | %s us | %s us |\n| on | %s us | %s us |\n",
              fmt(median(off50)).c_str(), fmt(median(off99)).c_str(), fmt(median(on50)).c_str(),
              fmt(median(on99)).c_str());
  std::printf("| on / off | %s x | %s x |\n", fmt(median(on50) / median(off50), 2).c_str(),
              fmt(median(on99) / median(off99), 2).c_str());
  std::printf("\nsecure runs: late %s %% (median)\n", fmt(100.0 * median(late_on), 3).c_str());
  return failures;
}

int benchMain(const Options& opt) {
  app::installShutdownHandlers();
  const fs::path dir = opt.keep.empty() ? fs::temp_directory_path() / ("swa_bench_dds_" + std::to_string(::getpid()))
                                        : fs::path(opt.keep);
  fs::create_directories(dir);
  std::printf("bench_dds: logs in %s; load average at start %s; %u CPUs; profiles %s\n", dir.c_str(),
              loadAverage().c_str(), std::thread::hardware_concurrency(), dds::resolveProfilesFile().c_str());
  std::fflush(stdout);
  const bool all = opt.only.empty();
  int failures = 0;
  if (all || opt.only == "latency" || opt.only == "pingpong") failures += latencySection(opt, dir);
  // No DDS participant lives in this process from here on: signals may land in this thread.
  app::acceptShutdownSignals();
  if ((all || opt.only == "lockstep") && !app::shutdownRequested()) failures += lockstepSection(opt, dir);
  if ((all || opt.only == "scale") && !app::shutdownRequested()) failures += scaleSection(opt, dir);
  if (opt.only == "security" && !app::shutdownRequested()) failures += securitySection(opt, dir);
  std::printf("\nload average at end %s\n", loadAverage().c_str());
  if (opt.keep.empty()) fs::remove_all(dir);
  return failures == 0 && !app::shutdownRequested() ? 0 : 1;
}

}  // namespace
}  // namespace swa::bench

int main(int argc, char** argv) {
  try {
    if (argc == 5 && std::string(argv[1]) == "--echo") {
      return swa::bench::echoMain(std::atoi(argv[2]), argv[3], std::atoi(argv[4]));
    }
    const swa::bench::Options opt = swa::bench::parseOptions(argc, argv);
    if (opt.help) {
      std::fputs(swa::app::helpText(swa::bench::makeCli).c_str(), stdout);
      return 0;
    }
    return swa::bench::benchMain(opt);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_dds: %s\n", e.what());
    return 2;
  }
}
