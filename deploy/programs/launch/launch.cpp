#include "launch.h"

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <set>

#include "child_process.h"
#include "shm_janitor.h"
#include "swa/app/run_directory.h"

namespace swa::launch {

namespace fs = std::filesystem;

int Launch::run() {
  // What is in --out before this run is not the run's: the marker written at the end lists only what appeared since.
  const std::set<std::string> before = app::entriesOf(o_.out_dir);
  const auto mark = [&] {
    try {
      app::markRunDirectory(o_.out_dir, before);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "swa_launch: %s (the next launch here will not remove this run's files)\n", e.what());
    }
  };
  const ShmJanitor janitor;
  std::vector<RunOutcome> outcomes;
  std::unique_ptr<ChildProcess> server;
  const auto stopServer = [&server, this] {
    if (!server) return;
    server->signal(SIGINT);  // on SIGTERM fast-discovery-server would leave its /dev/shm files
    for (int k = 0; k < static_cast<int>(o_.grace_s * 50) && server->running(); ++k) ::usleep(20000);
    server.reset();  // SIGKILLs it if still running
  };
  try {
    if (!discovery_server_.empty()) {
      std::error_code ec;
      fs::create_directories(o_.out_dir, ec);
      server =
          std::make_unique<ChildProcess>(discovery_server_, (fs::path(o_.out_dir) / "discovery_server.log").string());
      std::printf("swa_launch: discovery server on %s (log %s)\n", std::getenv("SWA_DISCOVERY_SERVER"),
                  (fs::path(o_.out_dir) / "discovery_server.log").c_str());
    }
    for (const RunSpec& spec : runs_) {
      if (stop_) break;
      outcomes.push_back(superviseRun(o_, bin_, domain_, spec, stop_));
      const RunOutcome& r = outcomes.back();
      const std::string bridges = spec.scenario.vehicle.interface != sim::VehicleInterface::kDirect
                                      ? ", " + std::to_string(r.bridge_restarts) + " bridge restart(s)"
                                      : "";
      std::printf("swa_launch [%s]: %s%s; %d agent restart(s)%s; %s\n", spec.label.c_str(),
                  r.verdict.empty() ? "no verdict" : r.verdict.c_str(), r.interrupted ? " (interrupted)" : "",
                  r.restarts, bridges.c_str(), (spec.dir / "report.html").c_str());
      // Why, on the console: a FAIL is not left to the report.
      for (const std::string& why : r.verdict_reasons) {
        std::printf("swa_launch [%s]:   %s\n", spec.label.c_str(), why.c_str());
      }
      if (runs_.size() > 1 && spec.scenario.agent.mode == agent::Mode::kStandalone && r.verdict == "FAIL") {
        std::printf(
            "swa_launch [%s]: as expected of the baseline: without GNSS each UAV flies on its own dead "
            "reckoning, which is what SWA is compared with\n",
            spec.label.c_str());
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "swa_launch: %s\n", e.what());
    stopServer();
    janitor.clean();
    mark();
    return 3;
  }
  stopServer();
  int status = outcomes.empty() ? 3 : outcomes.front().monitor_status;

  if (runs_.size() > 1 && outcomes.size() == runs_.size()) {
    // One report with both runs_ side by side (the paper's comparison).
    std::vector<std::string> argv_combine{bin_.monitor, "--combine"};
    for (const RunSpec& r : runs_) argv_combine.push_back(r.label + "=" + r.dir.string());
    argv_combine.push_back("--out");
    argv_combine.push_back(o_.out_dir);
    argv_combine.push_back("--scenario");
    argv_combine.push_back((runs_.front().dir / "scenario.yaml").string());
    ChildProcess combine(argv_combine, (fs::path(o_.out_dir) / "combine.log").string());
    while (combine.running()) ::usleep(20000);
    const int c = combine.poll().value_or(-1);
    if (c == 0 || c == 1 || c == 3) {
      std::printf("swa_launch: comparison report %s\n", (fs::path(o_.out_dir) / "report.html").c_str());
    } else {
      std::printf("swa_launch: the comparison report failed (%s, see %s)\n", describeStatus(c).c_str(),
                  (fs::path(o_.out_dir) / "combine.log").c_str());
      if (status == 0) status = 3;
    }
  }
  const std::vector<std::string> removed = janitor.clean();
  if (!removed.empty()) {
    std::printf("swa_launch: removed %zu shared-memory file(s) left by killed processes\n", removed.size());
  }
  mark();
  return status;
}

}  // namespace swa::launch
