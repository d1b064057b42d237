#include "run_supervisor.h"

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "child_process.h"
#include "restart_policy.h"
#include "run_files.h"
#include "swa/app/signals.h"
#include "swa/run_record/run_dir.h"

namespace swa::launch {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr auto kPollPeriod = std::chrono::milliseconds(20);
// The monitor ends on the simulator's EVENT_SCENARIO_END; this bounds the wait when it never arrives.
constexpr double kMonitorAfterSimS = 30.0;
// The simulator waits for acknowledgments before it exits (swa::dds::Participant): bounded by about 6 s.
constexpr double kSimAfterMonitorS = 15.0;
// Ctrl-C / SIGTERM ends any launch within 15 s, also 100 processes on a starved host (measured before this bound:
// 53 s for 100 agents during a discovery storm): the simulator and monitor get this long to end the run and write
// the report, then every child at most kStopGraceS (or --grace-s if shorter) before it is killed.
constexpr double kFinishAfterStopS = 8.0;
constexpr double kStopGraceS = 5.0;

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// A process of one UAV, supervised and restarted alike: its agent, or (vehicle.interface = px4, ardupilot) its
// autopilot bridge.
struct UavProcess {
  bool bridge = false;
  int uav = 0;
  std::unique_ptr<ChildProcess> process;
  int restarts = 0;
  std::optional<Clock::time_point> restart_due;
  bool given_up = false;
  int last_exit = 0;  // of the process being restarted (restarts.csv)
  double last_backoff = 0.0;

  std::string name() const { return (bridge ? "bridge " : "agent ") + std::to_string(uav); }
  std::string logName() const { return (bridge ? "bridge_" : "agent_") + std::to_string(uav) + ".log"; }
  // The uav column of restarts.csv (swa/run_record/restarts.h).
  std::string subject() const { return (bridge ? "bridge_" : "") + std::to_string(uav); }
};

class Supervisor {
 public:
  Supervisor(const LaunchOptions& options, const Binaries& bin, int domain, const RunSpec& spec,
             const std::atomic<bool>& stop)
      : o_(options),
        stop_(stop),
        bin_(bin),
        domain_(std::to_string(domain)),
        spec_(spec),
        logs_(spec.dir / "logs"),
        policy_(options.max_restarts, options.restart_backoff_s, options.restart_backoff_max_s) {
    const bool autopilot = spec.scenario.vehicle.interface != sim::VehicleInterface::kDirect;
    for (const bool bridge : {false, true}) {
      if (bridge && !autopilot) break;
      for (int i = 0; i < spec.scenario.uav_count; ++i) {
        UavProcess& p = uav_processes_.emplace_back();
        p.bridge = bridge;
        p.uav = i;
      }
    }
  }

  RunOutcome run() {
    prepareRunDirectory(spec_, logs_);
    t0_ = Clock::now();
    const char* swarm = std::getenv("SWA_SWARM");
    const sim::VehicleInterface vehicle = spec_.scenario.vehicle.interface;
    const char* bridges = vehicle == sim::VehicleInterface::kPx4         ? " + their PX4 bridges"
                          : vehicle == sim::VehicleInterface::kArdupilot ? " + their ArduPilot bridges"
                                                                         : "";
    std::printf("swa_launch [%s]: sim + %d agents%s + monitor on DDS domain %s, swarm %s, logs in %s\n",
                spec_.label.c_str(), spec_.scenario.uav_count, bridges, domain_.c_str(),
                swarm != nullptr && *swarm ? swarm : "(default partition)", logs_.c_str());
    if (!o_.live.empty()) {
      // The monitor listens on ADDR (127.0.0.1 unless given); 0.0.0.0 is reached through this host's loopback too.
      const std::size_t colon = o_.live.rfind(':');
      std::string host = colon == std::string::npos ? "127.0.0.1" : o_.live.substr(0, colon);
      if (host == "0.0.0.0") host = "127.0.0.1";
      const std::string port = colon == std::string::npos ? o_.live : o_.live.substr(colon + 1);
      if (port == "0") {
        std::printf("swa_launch [%s]: live view on a free port: its URL is in %s\n", spec_.label.c_str(),
                    (logs_ / "monitor.log").c_str());
      } else {
        std::printf("swa_launch [%s]: live view at http://%s:%s/ (Foxglove, Lichtblick: ws://%s:%s)\n",
                    spec_.label.c_str(), host.c_str(), port.c_str(), host.c_str(), port.c_str());
      }
    }
    std::fflush(stdout);
    startMonitor();
    const double stagger_s = staggerOf(o_);
    if (stagger_s > 0.0) startSim();  // the hub first: each UAV process then authenticates against settled peers
    for (std::size_t k = 0; k < uav_processes_.size(); ++k) {
      if (stagger_s > 0.0 && k > 0) pause(stagger_s);  // returns at once once a stop is asked
      start(uav_processes_[k]);
    }
    if (stagger_s == 0.0) startSim();
    supervise();
    stopAll();
    outcome_.verdict = record::recordedVerdict(spec_.dir.string());
    outcome_.verdict_reasons = record::recordedVerdictReasons(spec_.dir.string());
    return outcome_;
  }

 private:
  std::string scenarioFile() const { return launch::scenarioFile(spec_); }
  std::string agentConfigFile() const { return launch::agentConfigFile(spec_); }

  std::vector<std::string> scenarioArgs() const { return {"--scenario", scenarioFile(), "--domain", domain_}; }

  void startMonitor() {
    if (monitor_restarts_ > 0) {
      std::ofstream(logs_ / "monitor.log", std::ios::app)
          << "\n==== swa_launch: restart " << monitor_restarts_ << " at " << secondsSince(t0_) << " s ====\n";
    }
    std::vector<std::string> argv{bin_.monitor};
    for (const std::string& a : scenarioArgs()) argv.push_back(a);
    for (const std::string& a : {std::string("--label"), spec_.label, std::string("--out"), spec_.dir.string(),
                                 std::string("--restarts"), (logs_ / "restarts.csv").string()}) {
      argv.push_back(a);
    }
    if (o_.record) {
      // A restarted monitor must not overwrite what the previous one recorded.
      const std::string file =
          monitor_restarts_ == 0 ? "run.mcap" : "run_restart" + std::to_string(monitor_restarts_) + ".mcap";
      argv.push_back("--record");
      argv.push_back((spec_.dir / file).string());
      argv.push_back("--record-set");
      argv.push_back(recording::toString(o_.record_set));
    }
    if (!o_.live.empty()) {
      argv.push_back("--live");
      argv.push_back(o_.live);
    }
    monitor_ = std::make_unique<ChildProcess>(argv, (logs_ / "monitor.log").string());
  }

  // Waits `s` seconds, or less if a stop is asked meanwhile.
  void pause(double s) const {
    const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
    while (!stop_ && Clock::now() < until) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }

  void startSim() {
    std::vector<std::string> argv{bin_.sim};
    for (const std::string& a : scenarioArgs()) argv.push_back(a);
    for (const std::string& a : {std::string("--wait-monitors"), std::string("1"), std::string("--agent-timeout-s"),
                                 std::to_string(o_.agent_timeout_s), std::string("--summary-out"),
                                 (spec_.dir / "sim_summary.json").string()}) {
      argv.push_back(a);
    }
    sim_ = std::make_unique<ChildProcess>(argv, (logs_ / "sim.log").string());
  }

  void start(UavProcess& p) {
    const fs::path log = logs_ / p.logName();
    if (p.restarts > 0) {
      std::ofstream(log, std::ios::app) << "\n==== swa_launch: restart " << p.restarts << " at " << secondsSince(t0_)
                                        << " s ====\n";
    }
    // A bridge engages the autopilot itself (PX4: offboard; ArduPilot: GUIDED): the simulator's stand-ins start in
    // Hold / LOITER, as a real vehicle would be handed over by its pilot. It speaks the release the PX4 stand-ins play,
    // and forwards their GNSS only when they report it (vehicle.gnss_source = autopilot; otherwise the simulator
    // publishes swa/uav<i>/gnss itself).
    const std::string uav = std::to_string(p.uav);
    const sim::VehicleSetup& vehicle = spec_.scenario.vehicle;
    std::vector<std::string> argv =
        p.bridge
            ? std::vector<std::string>{bin_.bridge,
                                       "--id",
                                       uav,
                                       "--domain",
                                       domain_,
                                       "--engage",
                                       "--summary-out",
                                       (logs_ / ("bridge_" + uav + "_summary.json")).string()}
            : std::vector<std::string>{bin_.agent, "--id", uav, "--domain", domain_, "--config", agentConfigFile()};
    if (p.bridge && vehicle.interface == sim::VehicleInterface::kArdupilot) {
      // The stand-ins write the ROS order. Told, not found out: a stand-in facing north looks level in either order,
      // and in the simulator nobody turns it by hand (--ap-quaternion auto would wait).
      argv.insert(argv.end(), {"--autopilot", "ardupilot", "--ap-quaternion", "ros"});
    } else if (p.bridge) {
      argv.insert(argv.end(), {"--px4-release", px4::releaseName(vehicle.px4_release)});
    }
    if (p.bridge && vehicle.gnss_source != sim::GnssSource::kAutopilot) argv.emplace_back("--no-gnss");
    if (p.bridge) {
      argv.insert(argv.end(), {"--odometry", vehicle.odometry == autopilot::OdometryMode::kOff      ? "off"
                                             : vehicle.odometry == autopilot::OdometryMode::kAlways ? "always"
                                                                                                    : "gnss-loss"});
    }
    p.process = std::make_unique<ChildProcess>(argv, log.string());
  }

  void requestStop(const char* why) {
    if (stopping_) return;
    stopping_ = true;
    stopped_at_ = Clock::now();
    outcome_.interrupted = true;
    std::printf("swa_launch [%s]: %s: ending the run\n", spec_.label.c_str(), why);
    std::fflush(stdout);
    // The simulator first: it publishes EVENT_SCENARIO_END ("interrupted"), so the monitor writes what it has.
    if (sim_) sim_->signal(SIGTERM);
  }

  void superviseUavProcesses() {
    for (UavProcess& p : uav_processes_) {
      if (!p.process || p.given_up) continue;
      const std::optional<int> status = p.process->poll();
      if (!status) continue;
      if (!p.restart_due) {
        if (!policy_.allowed(p.restarts)) {
          p.given_up = true;
          std::printf("swa_launch [%s]: %s ended (%s); %d restarts used, leaving it down\n", spec_.label.c_str(),
                      p.name().c_str(), describeStatus(*status).c_str(), p.restarts);
          std::fflush(stdout);
          continue;
        }
        const double delay = policy_.delay(p.restarts);
        p.restart_due =
            Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(delay));
        std::printf("swa_launch [%s]: %s ended (%s) at %.1f s; restarting in %.1f s\n", spec_.label.c_str(),
                    p.name().c_str(), describeStatus(*status).c_str(), secondsSince(t0_), delay);
        std::fflush(stdout);
        p.last_exit = *status;
        p.last_backoff = delay;
        continue;
      }
      if (Clock::now() < *p.restart_due) continue;
      p.restart_due.reset();
      ++p.restarts;
      ++(p.bridge ? outcome_.bridge_restarts : outcome_.restarts);
      std::ofstream(logs_ / "restarts.csv", std::ios::app)
          << secondsSince(t0_) << ',' << p.subject() << ',' << p.last_exit << ',' << p.restarts << ',' << p.last_backoff
          << '\n';
      start(p);
    }
  }

  void supervise() {
    std::optional<Clock::time_point> sim_done_at, monitor_done_at;
    while (true) {
      if (stop_)
        requestStop(app::shutdownSignal() == SIGINT ? "SIGINT" : app::shutdownSignal() == 0 ? "stop" : "SIGTERM");
      if (o_.timeout_s > 0.0 && secondsSince(t0_) > o_.timeout_s) requestStop("--timeout-s reached");

      if (!sim_done_at) {
        if (const auto s = sim_->poll()) {
          sim_done_at = Clock::now();
          outcome_.sim_status = *s;
          if (*s != 0 && !stopping_) {
            std::printf("swa_launch [%s]: swa_sim ended with %s (see %s)\n", spec_.label.c_str(),
                        describeStatus(*s).c_str(), (logs_ / "sim.log").c_str());
          }
        }
      }
      if (monitor_restart_due_) {
        if (Clock::now() >= *monitor_restart_due_) {
          monitor_restart_due_.reset();
          ++monitor_restarts_;
          std::ofstream(logs_ / "restarts.csv", std::ios::app)
              << secondsSince(t0_) << ",monitor," << monitor_exit_ << ',' << monitor_restarts_ << ','
              << monitor_backoff_s_ << '\n';
          startMonitor();
        }
      } else if (const auto m = monitor_->poll()) {
        if (sim_done_at) break;
        if (*m != 0 && *m != 1 && *m != 3) {
          // Crashed or killed before the end: started again like an agent. The new monitor scores what it can still
          // get (the simulator's truth history reaches 100 s back) and names what it missed (truth_coverage.h).
          if (!stopping_ && policy_.allowed(monitor_restarts_)) {
            const double delay = policy_.delay(monitor_restarts_);
            std::printf("swa_launch [%s]: swa_monitor ended (%s) at %.1f s; restarting it in %.1f s\n",
                        spec_.label.c_str(), describeStatus(*m).c_str(), secondsSince(t0_), delay);
            monitor_restart_due_ =
                Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(delay));
            monitor_exit_ = *m;
            monitor_backoff_s_ = delay;
            continue;
          }
          std::printf("swa_launch [%s]: swa_monitor failed with %s (see %s)\n", spec_.label.c_str(),
                      describeStatus(*m).c_str(), (logs_ / "monitor.log").c_str());
          requestStop("monitor gone");
          break;
        }
        // A verdict: the monitor has seen the end of the scenario, the simulator is finishing its own shutdown.
        if (!monitor_done_at) monitor_done_at = Clock::now();
        if (std::chrono::duration<double>(Clock::now() - *monitor_done_at).count() > kSimAfterMonitorS) {
          std::printf("swa_launch [%s]: swa_sim still running %.0f s after the monitor's verdict; stopping it\n",
                      spec_.label.c_str(), kSimAfterMonitorS);
          break;
        }
      }
      if (sim_done_at && std::chrono::duration<double>(Clock::now() - *sim_done_at).count() > kMonitorAfterSimS) {
        std::printf("swa_launch [%s]: no verdict from swa_monitor %.0f s after the simulator ended; stopping it\n",
                    spec_.label.c_str(), kMonitorAfterSimS);
        break;
      }
      if (stopping_ && secondsSince(*stopped_at_) > kFinishAfterStopS) {
        std::printf("swa_launch [%s]: the run has not ended %.0f s after it was stopped; stopping every process\n",
                    spec_.label.c_str(), kFinishAfterStopS);
        break;
      }
      // Restarting makes sense only while the world runs.
      if (!sim_done_at && !stopping_) superviseUavProcesses();
      std::fflush(stdout);
      std::this_thread::sleep_for(kPollPeriod);
    }
  }

  // SIGTERM to every child still running, then SIGKILL after the grace period; all reaped.
  void stopAll() {
    std::vector<ChildProcess*> all{sim_.get(), monitor_.get()};
    for (UavProcess& p : uav_processes_) all.push_back(p.process.get());
    // The monitor may still be writing its report: it gets the signal last among equals, after the sim.
    for (ChildProcess* c : all) {
      if (c != nullptr && c != monitor_.get()) c->signal(SIGTERM);
    }
    if (monitor_->running()) monitor_->signal(SIGTERM);
    const double grace_s = stopping_ ? std::min(o_.grace_s, kStopGraceS) : o_.grace_s;
    const auto deadline =
        Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(grace_s));
    while (Clock::now() < deadline) {
      bool any = false;
      for (ChildProcess* c : all) any = any || (c != nullptr && c->running());
      if (!any) break;
      std::this_thread::sleep_for(kPollPeriod);
    }
    for (ChildProcess* c : all) {
      if (c != nullptr && c->running()) {
        std::printf("swa_launch [%s]: pid %d did not stop within %.0f s; killing it\n", spec_.label.c_str(),
                    static_cast<int>(c->pid()), grace_s);
        c->signal(SIGKILL);
      }
    }
    for (ChildProcess* c : all) {
      while (c != nullptr && c->running()) std::this_thread::sleep_for(kPollPeriod);
    }
    const std::optional<int> m = monitor_->poll();
    outcome_.monitor_status = (m && (*m == 0 || *m == 1 || *m == 3)) ? *m : 3;
    if (outcome_.sim_status == -1) outcome_.sim_status = sim_->poll().value_or(-1);
  }

  const LaunchOptions& o_;
  const std::atomic<bool>& stop_;
  const Binaries& bin_;
  std::string domain_;
  RunSpec spec_;
  fs::path logs_;
  RestartPolicy policy_;
  Clock::time_point t0_;
  std::unique_ptr<ChildProcess> sim_, monitor_;
  int monitor_restarts_ = 0;
  int monitor_exit_ = 0;  // of the monitor process that is being restarted (restarts.csv)
  double monitor_backoff_s_ = 0.0;
  std::optional<Clock::time_point> monitor_restart_due_;
  std::vector<UavProcess> uav_processes_;  // the agents, then (px4, ardupilot) the bridges
  bool stopping_ = false;
  std::optional<Clock::time_point> stopped_at_;
  RunOutcome outcome_;
};

}  // namespace

RunOutcome superviseRun(const LaunchOptions& options, const Binaries& bin, int domain, const RunSpec& spec,
                        const std::atomic<bool>& stop) {
  return Supervisor(options, bin, domain, spec, stop).run();
}

}  // namespace swa::launch
