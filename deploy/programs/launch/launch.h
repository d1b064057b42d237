#pragma once
// swa_launch's process role: one run of the scenario as processes, or two for --compare (then one comparison
// report), with the discovery server it may start, supervised until the end or stop() (SIGINT / SIGTERM: forwarded,
// everything stopped and reaped, the shared-memory files of killed children removed).

#include <atomic>
#include <string>
#include <vector>

#include "launch_options.h"
#include "run_supervisor.h"
#include "swa/app/program.h"

namespace swa::launch {

class Launch : public app::Role {
 public:
  // `discovery_server`: the command line of a Fast DDS discovery server to start first (empty: none).
  Launch(LaunchOptions options, std::vector<RunSpec> runs, Binaries bin, int domain,
         std::vector<std::string> discovery_server)
      : o_(std::move(options)),
        runs_(std::move(runs)),
        bin_(std::move(bin)),
        domain_(domain),
        discovery_server_(std::move(discovery_server)) {}

  // The first run's verdict (0 PASS, 1 FAIL, 3 INCOMPLETE, also when nothing could be started).
  int run() override;
  void stop() override { stop_ = true; }

 private:
  const LaunchOptions o_;
  const std::vector<RunSpec> runs_;
  const Binaries bin_;
  const int domain_;
  const std::vector<std::string> discovery_server_;
  std::atomic<bool> stop_{false};
};

}  // namespace swa::launch
