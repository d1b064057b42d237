// swa_launch: a scenario as processes (sim, one agent per UAV, monitor), supervised. See --help (launch_options.cpp).

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "child_process.h"
#include "launch.h"
#include "launch_options.h"
#include "run_supervisor.h"
#include "shm_janitor.h"
#include "swa/agent/config_io.h"
#include "swa/app/program.h"
#include "swa/app/run_directory.h"
#include "swa/app/udp_port.h"
#include "swa/dds/deployment.h"
#include "swa/dds/options.h"
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
Binaries findBinaries(const std::string& bin_dir, bool bridges, std::vector<std::string>& problems) {
  const fs::path dir = bin_dir.empty() ? ownDirectory() : fs::path(bin_dir);
  Binaries b{(dir / "swa_sim").string(), (dir / "swa_agent").string(), (dir / "swa_monitor").string(),
             (dir / "swa_px4_bridge").string()};
  std::vector<std::string> needed{b.sim, b.agent, b.monitor};
  if (bridges) needed.push_back(b.bridge);
  for (const std::string& p : needed) {
    if (::access(p.c_str(), X_OK) != 0) problems.push_back("no executable " + p + " (build first, or --bin-dir)");
  }
  return b;
}

// How every child joins DDS (swa/dds/deployment.h), decided here once and passed down through the environment.
// Returns the discovery server to start, empty if none. Throws std::invalid_argument / std::runtime_error.
std::vector<std::string> applyDeployment(const LaunchOptions& o, int max_uav_count, bool bridges) {
  const int uav_processes = max_uav_count * (bridges ? 2 : 1);
  if (const auto automatic = automaticTransport(o, std::getenv("SWA_TRANSPORT"), uav_processes)) {
    ::setenv("SWA_TRANSPORT", automatic->c_str(), 1);
    std::printf(
        "swa_launch: %d UAV processes: discovery through a discovery server (past %d on one host it starts "
        "and steps faster than multicast discovery; --transport local forces that)\n",
        uav_processes, kMaxUavProcessesForSimpleDiscovery);
  }
  if (!o.transport.empty()) ::setenv("SWA_TRANSPORT", o.transport.c_str(), 1);
  if (!o.discovery_server.empty()) ::setenv("SWA_DISCOVERY_SERVER", o.discovery_server.c_str(), 1);
  if (!o.naming.empty()) ::setenv("SWA_NAMING", o.naming.c_str(), 1);
  if (!o.ros_namespace.empty()) ::setenv("SWA_ROS_NAMESPACE", o.ros_namespace.c_str(), 1);
  std::vector<std::string> server;
  const char* transport = std::getenv("SWA_TRANSPORT");
  const char* servers = std::getenv("SWA_DISCOVERY_SERVER");
  if (transport != nullptr && std::string(transport) == "discovery-server" && (servers == nullptr || !*servers)) {
    const std::string exe = "/usr/bin/fast-discovery-server";
    if (::access(exe.c_str(), X_OK) != 0) {
      throw std::runtime_error("no " + exe +
                               " to start a discovery server (apt-get install fastdds-tools), or "
                               "pass --discovery-server IP:PORT of a running one");
    }
    // Another launch's server may hold the default port (a shared host): the next free one, unless one was asked for.
    const std::optional<int> free_port =
        o.discovery_port ? std::optional<int>(*o.discovery_port) : app::firstFreeUdpPort(kDefaultDiscoveryPort, 100);
    if (!free_port) {
      throw std::runtime_error("no free UDP port in " + std::to_string(kDefaultDiscoveryPort) + ".." +
                               std::to_string(kDefaultDiscoveryPort + 99) +
                               " for the discovery server (--discovery-port)");
    }
    const std::string port = std::to_string(*free_port);
    ::setenv("SWA_DISCOVERY_SERVER", ("127.0.0.1:" + port).c_str(), 1);
    server = {exe, "-i", "0", "-l", "127.0.0.1", "-p", port};
  }
  if (!o.secure_dir.empty()) {
    std::error_code ec;
    const fs::path dir = fs::absolute(o.secure_dir, ec);
    std::vector<std::string> names{"swa_sim", "swa_monitor"};
    for (int i = 0; i < max_uav_count; ++i) names.push_back("swa_agent_" + std::to_string(i));
    for (int i = 0; bridges && i < max_uav_count; ++i) names.push_back("swa_bridge_" + std::to_string(i));
    std::string missing;
    for (const std::string& n : names) {
      for (const std::string& f : dds::unreadableFiles(dds::securityFiles(dir.string(), n))) {
        if (missing.find(f) == std::string::npos) missing += "\n  " + f;
      }
    }
    if (!missing.empty()) {
      throw std::runtime_error("--secure " + o.secure_dir + ": missing credentials:" + missing +
                               "\n(create them with: deploy/security/make-credentials.sh " +
                               std::string(bridges ? "--bridges " : "") + o.secure_dir + " " +
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
    const auto ms =
        std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::system_clock::now().time_since_epoch())
            .count();
    const std::string name = "launch-" + std::to_string(::getpid()) + "-" + std::to_string(ms % 1'000'000'000);
    ::setenv("SWA_SWARM", name.c_str(), 1);
  }
  dds::resolveDeployment();  // the combination as the children will see it
  return server;
}

std::string originOf(const LaunchOptions& o) {
  std::string origin = o.scenario_path;
  for (const std::string& set : o.overrides) origin += " --set " + set;
  if (!o.vehicle.empty()) origin += " --vehicle " + o.vehicle;
  return origin;
}

app::Plan prepare(const std::vector<std::string>& args) {
  // Everything that can be wrong is found before any process starts.
  const LaunchOptions o = parseLaunchOptions(args);
  if (auto done = app::printIf(o.help, launchUsage)) return *done;
  std::vector<RunSpec> runs;
  const int domain = dds::resolveDomain(o.domain);
  // The user's files are read once, here; each run's directory gets the effective scenario (run_supervisor.h).
  std::vector<std::string> overrides = o.overrides;
  if (!o.vehicle.empty()) overrides.push_back("vehicle.interface=" + o.vehicle);
  const sim::Scenario base = sim::loadScenario(o.scenario_path, overrides);
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
  const bool bridges = base.vehicle.interface != sim::VehicleInterface::kDirect;
  const std::vector<std::string> discovery_server = applyDeployment(o, base.uav_count, bridges);
  std::vector<std::string> problems;
  const Binaries bin = findBinaries(o.bin_dir, bridges, problems);
  if (!problems.empty()) {
    std::string all;
    for (const std::string& p : problems) all += (all.empty() ? "" : "\n") + p;
    throw std::runtime_error(all);
  }
  // Last: a run refused for another reason writes (and removes) nothing.
  app::claimRunDirectory(o.out_dir);
  monitor::prepareOutputDir(o.out_dir);
  return app::startWith(
      [o, runs, bin, domain, discovery_server]() -> std::unique_ptr<app::Role> {
        return std::make_unique<Launch>(o, runs, bin, domain, discovery_server);
      },
      3);
}

}  // namespace
}  // namespace swa::launch

int main(int argc, char** argv) {
  return swa::app::runProgram("swa_launch", "scenario", argc, argv, swa::launch::prepare);
}
