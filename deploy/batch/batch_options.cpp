#include "batch_options.h"

#include "swa/app/cli.h"

namespace swa::batch {
namespace {

app::Cli makeCli(BatchOptions& o) {
  app::Cli cli("swa_batch", "Monte Carlo runs of the simulator with N in-process agent cores.");
  cli.usage(R"(swa_batch --scenario FILE [--set key=value]... [--seeds N] [--jobs J] [--out DIR]
                 [--compare standalone|swa|anchored])");
  cli.details(R"(Runs the simulator and one SWA agent core per UAV in one process, deterministically per seed, seeds in parallel.
Prints one line per finished seed and an aggregate table; writes DIR/summary.json (aggregate and per seed) and
DIR/<mode>/seed_<S>.csv (time series, one row per 100 ms) and DIR/<mode>/seed_<S>_events.csv (GNSS loss,
collisions, failsafe).)");
  cli.scenario(o.scenario_path, "scenario YAML (see deploy/scenarios/)");
  cli.required("--scenario");
  cli.overrides(o.overrides, "override any scenario key, e.g. --set uav_count=16 --set imu.bias_std=0.15");
  cli.integer("--seeds", "N", o.seeds, 1, 100000, "a count", "number of seeds, starting at the scenario's `seed`");
  cli.integer("--jobs", "J", o.jobs, 1, 256, "a count", "seeds run in parallel; this machine has 2 cores");
  cli.path("--out", "DIR", o.out_dir, "output directory");
  cli.choice("--compare", "MODE", {agent::Mode::kStandalone, agent::Mode::kSwa, agent::Mode::kAnchored}, o.compare,
             "also run the same seeds with agent.mode = MODE and print both side by side");
  cli.answer("--parameters", o.list_parameters, "list every scenario key with unit, default and bounds, then exit");
  cli.footer("Exit status: 0 when every seed ran, 2 for a usage or scenario error, 1 when a run failed.");
  return cli;
}

}  // namespace

BatchOptions parseBatchOptions(const std::vector<std::string>& args) { return app::parseOptions(args, makeCli); }

std::string batchUsage() { return app::helpText(makeCli); }

}  // namespace swa::batch
