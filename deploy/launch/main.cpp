// swa_launch: a scenario as processes (sim, one agent per UAV, monitor), supervised. See --help (launch_options.cpp).

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "child_process.h"
#include "launch_options.h"
#include "run_supervisor.h"
#include "shm_janitor.h"
#include "swa/agent/config_io.h"
#include "swa/dds/deployment.h"
#include "swa/dds/options.h"
#include "swa/dds/shutdown.h"
#include "swa/monitor/output_dir.h"
#include "swa/sim/scenario_io.h"

namespace swa::launch {
namespace {

namespace fs = std::filesystem;

fs::path ownDirectory() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path(".") : self.parent_path();
}

// Every executable present and runnable, or the list of what is not.
Binaries findBinaries(const std::string& bin_dir, std::vector<std::string>& problems) {
  const fs::path dir = bin_dir.empty() ? ownDirectory() : fs::path(bin_dir);
  Binaries b{(dir / "swa_sim").string(), (dir / "swa_agent").string(), (dir / "swa_monitor").string()};
  for (const std::string& p : {b.sim, b.agent, b.monitor}) {
    if (::access(p.c_str(), X_OK) != 0) problems.push_back("no executable " + p + " (build first, or --bin-dir)");
  }
  return b;
}

// How every child joins DDS (swa/dds/deployment.h), decided here once and passed down through the environment.
// Returns the discovery server to start, empty if none. Throws std::invalid_argument / std::runtime_error.
std::vector<std::string> applyDeployment(const LaunchOptions& o, int max_uav_count) {
  if (!o.transport.empty()) ::setenv("SWA_TRANSPORT", o.transport.c_str(), 1);
  if (!o.discovery_server.empty()) ::setenv("SWA_DISCOVERY_SERVER", o.discovery_server.c_str(), 1);
  std::vector<std::string> server;
  const char* transport = std::getenv("SWA_TRANSPORT");
  const char* servers = std::getenv("SWA_DISCOVERY_SERVER");
  if (transport != nullptr && std::string(transport) == "discovery-server" && (servers == nullptr || !*servers)) {
    const std::string exe = "/usr/bin/fast-discovery-server";
    if (::access(exe.c_str(), X_OK) != 0) {
      throw std::runtime_error("no " + exe + " to start a discovery server (apt-get install fastdds-tools), or "
                               "pass --discovery-server IP:PORT of a running one");
    }
    const std::string port = std::to_string(o.discovery_port);
    ::setenv("SWA_DISCOVERY_SERVER", ("127.0.0.1:" + port).c_str(), 1);
    server = {exe, "-i", "0", "-l", "127.0.0.1", "-p", port};
  }
  if (!o.secure_dir.empty()) {
    std::error_code ec;
    const fs::path dir = fs::absolute(o.secure_dir, ec);
    std::vector<std::string> names{"swa_sim", "swa_monitor"};
    for (int i = 0; i < max_uav_count; ++i) names.push_back("swa_agent_" + std::to_string(i));
    std::string missing;
    for (const std::string& n : names) {
      for (const std::string& f : dds::unreadableFiles(dds::securityFiles(dir.string(), n))) {
        if (missing.find(f) == std::string::npos) missing += "\n  " + f;
      }
    }
    if (!missing.empty()) {
      throw std::runtime_error("--secure " + o.secure_dir + ": missing credentials:" + missing +
                               "\n(create them with: deploy/security/make-credentials.sh " + o.secure_dir + " " +
                               std::to_string(max_uav_count) + ")");
    }
    ::setenv("SWA_SECURITY_DIR", dir.c_str(), 1);
  }
  if (o.swarm == "none") {
    ::unsetenv("SWA_SWARM");
  } else if (!o.swarm.empty()) {
    ::setenv("SWA_SWARM", o.swarm.c_str(), 1);
  } else if (std::getenv("SWA_SWARM") == nullptr && o.secure_dir.empty()) {
    // A name of our own: two launches on one domain (or anything else there) never exchange a sample.
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                        std::chrono::system_clock::now().time_since_epoch()).count();
    const std::string name = "launch-" + std::to_string(::getpid()) + "-" + std::to_string(ms % 1'000'000'000);
    ::setenv("SWA_SWARM", name.c_str(), 1);
  }
  dds::resolveDeployment();  // the combination as the children will see it
  return server;
}

std::string originOf(const LaunchOptions& o) {
  std::string origin = o.scenario_path;
  for (const std::string& set : o.overrides) origin += " --set " + set;
  return origin;
}

int launchMain(int argc, char** argv) {
  LaunchOptions o;
  std::vector<RunSpec> runs;
  Binaries bin;
  int domain = 0;
  std::vector<std::string> discovery_server;
  // Everything that can be wrong is found before any process starts.
  try {
    o = parseLaunchOptions(std::vector<std::string>(argv + 1, argv + argc));
    if (o.help) {
      std::fputs(launchUsage().c_str(), stdout);
      return 0;
    }
    domain = dds::resolveDomain(o.domain);
    // The user's files are read once, here; each run's directory gets the effective scenario (run_supervisor.h).
    const sim::Scenario base = sim::loadScenario(o.scenario_path, o.overrides);
    const fs::path out(o.out_dir);
    const std::string first = agent::toString(base.agent.mode);
    if (o.compare && *o.compare != base.agent.mode) {
      const std::string second = agent::toString(*o.compare);
      sim::Scenario other = base;
      other.agent.mode = *o.compare;
      runs.push_back({first, out / first, base, originOf(o)});
      runs.push_back({second, out / second, other, originOf(o) + " --compare " + second});
    } else {
      runs.push_back({first, out, base, originOf(o)});
    }
    discovery_server = applyDeployment(o, base.uav_count);
    std::vector<std::string> problems;
    bin = findBinaries(o.bin_dir, problems);
    if (!problems.empty()) {
      std::string all;
      for (const std::string& p : problems) all += (all.empty() ? "" : "\n") + p;
      throw std::runtime_error(all);
    }
    monitor::prepareOutputDir(o.out_dir);  // last: a run refused for another reason writes nothing
  } catch (const params::ConfigError& e) {
    std::fprintf(stderr, "swa_launch: invalid scenario:\n%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "swa_launch: %s\n(see swa_launch --help)\n", e.what());
    return 2;
  }

  dds::installShutdownHandlers();
  dds::acceptShutdownSignals();  // single-threaded: the flag is polled by the supervision loop
  const ShmJanitor janitor;
  std::vector<RunOutcome> outcomes;
  std::unique_ptr<ChildProcess> server;
  const auto stopServer = [&server, &o] {
    if (!server) return;
    server->signal(SIGINT);  // on SIGTERM fast-discovery-server would leave its /dev/shm files
    for (int k = 0; k < static_cast<int>(o.grace_s * 50) && server->running(); ++k) ::usleep(20000);
    server.reset();  // SIGKILLs it if still running
  };
  try {
    if (!discovery_server.empty()) {
      std::error_code ec;
      fs::create_directories(o.out_dir, ec);
      server = std::make_unique<ChildProcess>(discovery_server,
                                              (fs::path(o.out_dir) / "discovery_server.log").string());
      std::printf("swa_launch: discovery server on %s (log %s)\n", std::getenv("SWA_DISCOVERY_SERVER"),
                  (fs::path(o.out_dir) / "discovery_server.log").c_str());
    }
    for (const RunSpec& spec : runs) {
      if (dds::shutdownRequested()) break;
      outcomes.push_back(superviseRun(o, bin, domain, spec));
      const RunOutcome& r = outcomes.back();
      std::printf("swa_launch [%s]: %s%s; %d agent restart(s); %s\n", spec.label.c_str(),
                  r.verdict.empty() ? "no verdict" : r.verdict.c_str(), r.interrupted ? " (interrupted)" : "",
                  r.restarts, (spec.dir / "report.html").c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "swa_launch: %s\n", e.what());
    stopServer();
    janitor.clean();
    return 3;
  }
  stopServer();
  int status = outcomes.empty() ? 3 : outcomes.front().monitor_status;

  if (runs.size() > 1 && outcomes.size() == runs.size()) {
    // One report with both runs side by side (the paper's comparison).
    std::vector<std::string> argv_combine{bin.monitor, "--combine"};
    for (const RunSpec& r : runs) argv_combine.push_back(r.label + "=" + r.dir.string());
    argv_combine.push_back("--out");
    argv_combine.push_back(o.out_dir);
    argv_combine.push_back("--scenario");
    argv_combine.push_back((runs.front().dir / "scenario.yaml").string());
    ChildProcess combine(argv_combine, (fs::path(o.out_dir) / "combine.log").string());
    while (combine.running()) ::usleep(20000);
    const int c = combine.poll().value_or(-1);
    if (c == 0 || c == 1 || c == 3) {
      std::printf("swa_launch: comparison report %s\n", (fs::path(o.out_dir) / "report.html").c_str());
    } else {
      std::printf("swa_launch: the comparison report failed (%s, see %s)\n", describeStatus(c).c_str(),
                  (fs::path(o.out_dir) / "combine.log").c_str());
      if (status == 0) status = 3;
    }
  }
  const std::vector<std::string> removed = janitor.clean();
  if (!removed.empty()) {
    std::printf("swa_launch: removed %zu shared-memory file(s) left by killed processes\n", removed.size());
  }
  return status;
}

}  // namespace
}  // namespace swa::launch

int main(int argc, char** argv) { return swa::launch::launchMain(argc, argv); }
