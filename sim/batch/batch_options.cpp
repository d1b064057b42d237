#include "batch_options.h"

#include <charconv>
#include <sstream>
#include <stdexcept>

namespace swa::batch {
namespace {

bool parsePositive(const std::string& text, int max, int& out) {
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value < 1 || value > max) return false;
  out = value;
  return true;
}

}  // namespace

std::string batchUsage() {
  return R"(usage: swa_batch --scenario FILE [--set key=value]... [--seeds N] [--jobs J] [--out DIR]
                 [--compare standalone|swa|anchored]

Runs the simulator and one SWA agent core per UAV in one process, deterministically per seed, seeds in parallel.
Prints one line per finished seed and an aggregate table; writes DIR/summary.json (aggregate and per seed) and
DIR/<mode>/seed_<S>.csv (time series, one row per 100 ms) and DIR/<mode>/seed_<S>_events.csv (GNSS loss,
collisions, failsafe).

  --scenario FILE   scenario YAML (see deploy/scenarios/)
  --set key=value   override any scenario key, e.g. --set uav_count=16 --set imu.bias_std=0.15 (repeatable)
  --seeds N         number of seeds, starting at the scenario's `seed` (default 1)
  --jobs J          seeds run in parallel (default 1; this machine has 2 cores)
  --out DIR         output directory (default out/batch)
  --compare MODE    also run the same seeds with agent.mode = MODE and print both side by side
  --parameters      list every scenario key with unit, default and bounds, then exit
  --help            this text

Exit status: 0 when every seed ran, 2 for a usage or scenario error, 1 when a run failed.
)";
}

BatchOptions parseBatchOptions(const std::vector<std::string>& args) {
  BatchOptions o;
  std::vector<std::string> problems;
  auto value = [&](std::size_t& i, const std::string& flag) -> std::optional<std::string> {
    if (i + 1 >= args.size()) {
      problems.push_back(flag + " needs a value");
      return std::nullopt;
    }
    return args[++i];
  };
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--help" || a == "-h") {
      o.help = true;
    } else if (a == "--parameters") {
      o.list_parameters = true;
    } else if (a == "--scenario") {
      if (auto v = value(i, a)) o.scenario_path = *v;
    } else if (a == "--set") {
      if (auto v = value(i, a)) o.overrides.push_back(*v);
    } else if (a == "--seeds") {
      if (auto v = value(i, a); v && !parsePositive(*v, 100000, o.seeds))
        problems.push_back("--seeds must be an integer in [1, 100000], got '" + *v + "'");
    } else if (a == "--jobs") {
      if (auto v = value(i, a); v && !parsePositive(*v, 256, o.jobs))
        problems.push_back("--jobs must be an integer in [1, 256], got '" + *v + "'");
    } else if (a == "--out") {
      if (auto v = value(i, a)) o.out_dir = *v;
    } else if (a == "--compare") {
      if (auto v = value(i, a)) {
        if (*v == "standalone") {
          o.compare = agent::Mode::kStandalone;
        } else if (*v == "swa") {
          o.compare = agent::Mode::kSwa;
        } else if (*v == "anchored") {
          o.compare = agent::Mode::kAnchored;
        } else {
          problems.push_back("--compare must be standalone, swa or anchored, got '" + *v + "'");
        }
      }
    } else {
      problems.push_back("unknown argument '" + a + "'");
    }
  }
  if (!o.help && !o.list_parameters && o.scenario_path.empty()) problems.push_back("--scenario FILE is required");
  if (!problems.empty()) {
    std::ostringstream msg;
    for (const auto& p : problems) msg << "swa_batch: " << p << "\n";
    msg << "try 'swa_batch --help'";
    throw std::invalid_argument(msg.str());
  }
  return o;
}

}  // namespace swa::batch
