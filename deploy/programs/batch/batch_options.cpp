#include "batch_options.h"

#include <stdexcept>

#include "swa/app/cli.h"

namespace swa::batch {
namespace {

app::Cli makeCli(BatchOptions& o) {
  app::Cli cli("swa_batch", "Monte Carlo runs of the simulator with N in-process agent cores.");
  cli.usage(R"(swa_batch --scenario FILE [--set key=value]... [--seeds N] [--jobs J] [--out DIR]
                 [--compare standalone|swa|anchored]
       swa_batch --scenario FILE [--set key=value]... --sweep KEY=V1,V2,... [--sweep ...] [--seeds N]
                 [--jobs J] [--shard I/N] [--out DIR] [--dry-run]
       swa_batch merge DIR... --out DIR)");
  cli.details(
      R"(Runs the simulator and one SWA agent core per UAV in one process, deterministically per seed, seeds in
parallel.
Prints one line per finished seed and an aggregate table; writes DIR/summary.json (aggregate and per seed) and
DIR/<mode>/seed_<S>.csv (time series, one row per 100 ms) and DIR/<mode>/seed_<S>_events.csv (GNSS loss,
collisions, failsafe).

A study: --sweep KEY=V1,V2,... (any scenario key, as --set takes it; repeat for more keys) runs every combination
of the values (the grid) for every seed, on every core unless --jobs says otherwise, with a progress line and ETA.
It writes into DIR: study.html (read it first: each key metric plotted against each swept key, and the mean ± sd
of every grid point), runs.csv (tidy: one row per run, the swept keys, seed, and every summary metric; pandas and R
read it as is), points/<k>/summary.json (per grid point: its values and the aggregate over its seeds), and
study.json (the study id, version, plan, base scenario, every run). --shard I/N runs only the runs whose index
(point * seeds + seed offset) is I - 1 modulo N and writes only study.json; `swa_batch merge SHARD_DIR... --out DIR`
then writes exactly the files the whole study would have written, and refuses shards of another study, version or
cut, a shard given twice, or a missing one. --out must not hold an older study.

A scenario file may carry the study itself, so a study is one file under version control (the other programs
ignore the section; see deploy/scenarios/study_drift_vs_n.yaml):
  study:
    seeds: 20
    sweep:
      uav_count: [4, 8, 16, 32]
      agent.formation.neighbourhood: [gabriel, k_nearest]
    variants:
      gabriel: {agent.formation.neighbourhood: gabriel,
                agent.focal.bias_window_s: 30}
      k3: {agent.formation.neighbourhood: k_nearest, agent.formation.k: 3}
Variants are one more axis, "variant", after the sweep's: named sets of overrides that each grid point runs in turn.
swa_batch --scenario FILE then runs the study; --sweep KEY=... replaces the file's values of KEY or adds an axis,
--variant NAME:KEY=V,... replaces the file's variant NAME or adds one, and --seeds replaces study.seeds.)");
  cli.scenario(o.scenario_path, "scenario YAML (see deploy/scenarios/)");
  cli.required("--scenario");
  cli.overrides(o.overrides, "override any scenario key, e.g. --set uav_count=16 --set imu.bias_std=0.15");
  cli.integer("--seeds", "N", o.seeds, 1, 100000, "a count",
              "number of seeds, starting at the scenario's `seed` (a study: at every grid point)");
  cli.integer("--jobs", "J", o.jobs, 1, 256, "a count", "seeds run in parallel; this machine has 2 cores");
  cli.path("--out", "DIR", o.out_dir, "output directory; the files an earlier run wrote there are removed first");
  cli.choice("--compare", "MODE", {agent::Mode::kStandalone, agent::Mode::kSwa, agent::Mode::kAnchored}, o.compare,
             "also run the same seeds with agent.mode = MODE and print both side by side");
  cli.list("--sweep", "KEY=V1,V2,...", o.sweeps, "sweep a scenario key over these values (a study; see below)");
  cli.list("--variant", "NAME:KEY=V,...", o.variants,
           "compare a named set of overrides, e.g. k3:agent.formation.neighbourhood=k_nearest,agent.formation.k=3 "
           "(a study: one more axis; see below)");
  cli.text("--shard", "I/N", o.shard, "run only shard I of N of the study (1 <= I <= N)", "I/N");
  cli.flag("--dry-run", o.dry_run,
           "check the scenario (a study: every grid point) and print what would run, then exit without running; "
           "deploy/slurm/submit-study.sh does this before it submits");
  cli.answer("--parameters", o.list_parameters, "list every scenario key with unit, default and bounds, then exit");
  cli.footer("Exit status: 0 when every seed ran, 2 for a usage or scenario error, 1 when a run failed.");
  return cli;
}

}  // namespace

namespace {

// swa_batch merge DIR... --out DIR
BatchOptions parseMerge(const std::vector<std::string>& args) {
  BatchOptions o;
  o.merge = true;
  o.out_dir.clear();
  std::vector<std::string> problems;
  for (std::size_t k = 1; k < args.size(); ++k) {
    const std::string& a = args[k];
    if (a == "--help" || a == "-h") {
      o.help = true;
    } else if (a == "--out" || a.rfind("--out=", 0) == 0) {
      if (a == "--out" && k + 1 < args.size()) {
        o.out_dir = args[++k];
      } else if (a != "--out") {
        o.out_dir = a.substr(6);
      } else {
        problems.push_back("--out needs a directory");
      }
    } else if (a.rfind("-", 0) == 0) {
      problems.push_back("merge takes shard directories and --out DIR, not " + a);
    } else {
      o.merge_dirs.push_back(a);
    }
  }
  if (o.help) return o;
  if (o.merge_dirs.empty()) problems.push_back("merge needs the shards' directories");
  if (o.out_dir.empty()) problems.push_back("merge needs --out DIR");
  if (!problems.empty()) {
    std::string text;
    for (const std::string& p : problems) text += (text.empty() ? "" : "\n") + p;
    throw std::invalid_argument(text);
  }
  return o;
}

}  // namespace

BatchOptions parseBatchOptions(const std::vector<std::string>& args) {
  if (!args.empty() && args.front() == "merge") return parseMerge(args);
  return app::parseOptions<BatchOptions>(args, makeCli, [](BatchOptions& o, const app::Cli& cli, app::Problems& p) {
    o.jobs_given = cli.given("--jobs");
    o.seeds_given = cli.given("--seeds");
    if (o.compare && o.study()) p.push_back("--compare is not for studies: sweep agent.mode instead");
  });
}

std::string batchUsage() { return app::helpText(makeCli); }

}  // namespace swa::batch
