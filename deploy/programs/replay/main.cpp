// swa_replay: a recorded run (MCAP) replayed into agents over DDS, or re-run through the agent core in-process and
// compared command by command (--check). See --help (replay_options.cpp).

#include <cstdio>
#include <memory>
#include <stdexcept>

#include "recorded_run.h"
#include "replay_check.h"
#include "replay_node.h"
#include "replay_options.h"
#include "swa/app/program.h"
#include "swa/dds/options.h"
#include "swa/recording/record_set.h"
#include "swa/sim/scenario_io.h"

namespace swa::replay {
namespace {

agent::AgentConfig checkConfig(const ReplayOptions& o, const RecordedRun& run) {
  if (!o.scenario_path.empty()) return sim::loadScenario(o.scenario_path, o.overrides).agent;
  if (!run.scenario_yaml) {
    throw std::invalid_argument(o.file + " carries no scenario (recorded without one): give --scenario FILE");
  }
  return sim::parseRecordedScenario(*run.scenario_yaml, o.file + " (its recorded scenario)", o.overrides).agent;
}

app::Plan prepare(const std::vector<std::string>& args) {
  const ReplayOptions options = parseReplayOptions(args);
  if (auto done = app::printIf(options.help, replayUsage)) return *done;
  RecordedRun run = readRecordedRun(options.file, options.uav, !options.check && !options.uav);
  if (run.truncated) {
    std::fprintf(stderr, "swa_replay: %s ends early (a recorder that crashed): read up to its last whole record\n",
                 options.file.c_str());
  }
  if (run.record_set && *run.record_set != recording::toString(recording::RecordSet::kAll)) {
    // Without the sensors and commands there is nothing to re-run or re-send; say why rather than "no input".
    throw std::invalid_argument(options.file + " is a '" + *run.record_set + "' recording (swa_monitor --record-set " +
                                *run.record_set + ", swa_launch --record=" + *run.record_set +
                                "): it holds no sensors or commands; swa_replay needs a complete recording "
                                "(--record, the set 'all')");
  }
  if (options.uav && run.uavs.count(*options.uav) == 0) {
    throw std::invalid_argument(options.file + " has no input of UAV " + std::to_string(*options.uav));
  }
  if (run.uavs.empty()) throw std::invalid_argument(options.file + " has no agent input to replay");
  if (options.check) {
    const std::vector<UavCheck> checks = checkRun(run, checkConfig(options, run));
    std::printf("%s", formatChecks(checks).c_str());
    bool identical = true;
    for (const UavCheck& c : checks) identical = identical && c.identicalRun();
    return app::exitWith(identical ? kExitOk : kExitDifferent);
  }
  const int domain = dds::resolveDomain(options.domain);
  auto shared = std::make_shared<RecordedRun>(std::move(run));
  return app::startWith(
      [shared, options, domain]() -> std::unique_ptr<app::Role> {
        return std::make_unique<ReplayNode>(std::move(*shared), options, domain);
      },
      kExitBadInput);
}

}  // namespace
}  // namespace swa::replay

int main(int argc, char** argv) {
  return swa::app::runProgram("swa_replay", "scenario", argc, argv, swa::replay::prepare);
}
