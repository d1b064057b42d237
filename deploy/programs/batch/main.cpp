// swa_batch: Monte Carlo runs of the simulator with N in-process agent cores. See --help.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "batch_options.h"
#include "batch_runner.h"
#include "study_runner.h"
#include "swa/agent/config_io.h"
#include "swa/app/program.h"
#include "swa/app/run_directory.h"
#include "swa/app/version.h"
#include "swa/monitor/output_dir.h"
#include "swa/run_record/run_dir.h"
#include "swa/run_record/scoring.h"
#include "swa/sim/events.h"
#include "swa/sim/scenario_io.h"

namespace fs = std::filesystem;
using namespace swa;

namespace {

constexpr const char* kColumns[] = {
    "mean_neighbor_distance_m", "min_separation_m", "collisions",    "drift_velocity_mps",
    "uav_displacement_m",       "groups",           "anees_position"};
// With a mission (issue #45), also: the swarm's centroid against the plan, d_NB while moving, and each UAV's own end
// error and the scatter of their end points (what --compare standalone is read by).
constexpr const char* kMissionColumns[] = {"mission_end_error_m", "mission_path_error_m", "mission_d_nb_moving_m",
                                           "mission_uav_end_error_m", "mission_uav_end_spread_m"};

double field(const monitor::Summary& s, const std::string& key) {
  for (const auto& f : monitor::summaryFields(s))
    if (f.key == key) return f.value;
  return monitor::kNaN;
}

void printSeed(const batch::RunResult& r) {
  std::printf(
      "%-10s seed %-6llu d_NB %6.2f m  min_sep %6.2f m  collisions %3.0f  drift %.3f m/s  disp %6.2f m  "
      "groups %2.0f  ANEES_p %5.2f\n",
      agent::toString(r.mode).c_str(), static_cast<unsigned long long>(r.seed), field(r.summary, kColumns[0]),
      field(r.summary, kColumns[1]), field(r.summary, kColumns[2]), field(r.summary, kColumns[3]),
      field(r.summary, kColumns[4]), field(r.summary, kColumns[5]), field(r.summary, kColumns[6]));
  std::fflush(stdout);
}

record::Json modeJson(const std::vector<batch::RunResult>& runs) {
  std::vector<monitor::Summary> summaries;
  record::Json seeds = record::Json::array();
  for (const batch::RunResult& r : runs) {
    summaries.push_back(r.summary);
    record::Json seed{{"seed", r.seed}, {"rejected_inputs", r.rejected_inputs}};
    seed.update(record::metricsJson(r.summary));
    seeds.push_back(std::move(seed));
  }
  return record::Json{{"mode", agent::toString(runs.front().mode)},
                      {"aggregate", record::aggregateJson(monitor::aggregate(summaries))},
                      {"seeds", std::move(seeds)}};
}

// Per seed, the time series and the world's events, in the run directory's dialect (swa/run_record/run_dir.h).
void writeSeries(const fs::path& dir, const std::vector<batch::RunResult>& runs) {
  fs::create_directories(dir);
  for (const batch::RunResult& r : runs) {
    const std::string seed = "seed_" + std::to_string(r.seed);
    std::vector<sim::EventRecord> events;
    for (const sim::Event& e : r.events) events.push_back(sim::eventOf(e));
    record::writeTextFile((dir / (seed + "_events.csv")).string(), record::eventsCsv(events));
    record::writeTextFile((dir / (seed + ".csv")).string(), record::timeSeriesCsv(r.series));
  }
}

void printAggregate(const std::vector<std::vector<batch::RunResult>>& modes) {
  std::printf("\n%-26s", "metric (mean ± std)");
  for (const auto& runs : modes) std::printf("  %-24s", agent::toString(runs.front().mode).c_str());
  std::printf("\n");
  std::vector<monitor::Aggregate> aggs;
  for (const auto& runs : modes) {
    std::vector<monitor::Summary> s;
    for (const auto& r : runs) s.push_back(r.summary);
    aggs.push_back(monitor::aggregate(s));
  }
  std::vector<const char*> keys(std::begin(kColumns), std::end(kColumns));
  const monitor::Statistic* mission = aggs.front().find(kMissionColumns[0]);
  if (mission != nullptr && mission->runs > 0)
    keys.insert(keys.end(), std::begin(kMissionColumns), std::end(kMissionColumns));
  for (const char* key : keys) {
    std::printf("%-26s", key);
    for (const auto& a : aggs) {
      const monitor::Statistic* st = a.find(key);
      if (st && st->runs > 0) {
        std::printf("  %10.3f ± %-10.3f", st->mean, st->std);
      } else {
        std::printf("  %-24s", "n/a");
      }
    }
    std::printf("\n");
  }
}

// swa_batch as a process role: the seeds of every mode, then summary.json, the per-seed series and the report.
class Batch : public app::Role {
 public:
  Batch(batch::BatchOptions options, sim::Scenario scenario)
      : opt_(std::move(options)), scenario_(std::move(scenario)) {}
  int run() override;
  void stop() override { stop_ = true; }

 private:
  const batch::BatchOptions opt_;
  const sim::Scenario scenario_;
  std::atomic<bool> stop_{false};
};

int Batch::run() {
  const batch::BatchOptions& opt = opt_;
  const sim::Scenario& scenario = scenario_;
  std::vector<agent::Mode> modes{scenario.agent.mode};
  if (opt.compare && *opt.compare != scenario.agent.mode) modes.push_back(*opt.compare);
  std::printf("swa_batch: %s, %d UAVs, %.0f s, seeds %llu..%llu, %d job(s)\n", opt.scenario_path.c_str(),
              scenario.uav_count, scenario.duration_s, static_cast<unsigned long long>(scenario.seed),
              static_cast<unsigned long long>(scenario.seed + static_cast<std::uint64_t>(opt.seeds) - 1), opt.jobs);
  const auto wall0 = std::chrono::steady_clock::now();
  const std::clock_t cpu0 = std::clock();
  std::vector<std::vector<batch::RunResult>> results;
  for (agent::Mode m : modes) {
    sim::Scenario s = scenario;
    s.agent.mode = m;
    results.push_back(batch::runSeeds(s, opt.seeds, opt.jobs, printSeed, stop_));
  }
  if (stop_) {
    std::fprintf(stderr, "swa_batch: interrupted before every seed ran: nothing written\n");
    return 3;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const double cpu = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  printAggregate(results);

  const fs::path out(opt.out_dir);
  // An earlier run's files go (a --compare run's standalone/ would stay beside a run without it); the user's stay.
  app::claimRunDirectory(out);
  fs::create_directories(out);
  const std::set<std::string> before = app::entriesOf(out);
  record::Json summary{{"scenario", opt.scenario_path},
                       {"uav_count", scenario.uav_count},
                       {"duration_s", scenario.duration_s},
                       {"seeds", opt.seeds},
                       {"runs", record::Json::array()}};
  for (const std::vector<batch::RunResult>& runs : results) {
    summary["runs"].push_back(modeJson(runs));
    writeSeries(out / agent::toString(runs.front().mode), runs);
  }
  record::writeTextFile((out / record::kSummaryFile).string(), record::jsonText(summary));
  record::writeTextFile((out / record::kScenarioFile).string(), sim::scenarioToYaml(scenario));
  // The report shows the first seed of every mode side by side (the paper's comparison figure).
  std::vector<monitor::RunReport> report_runs;
  for (const auto& runs : results) {
    const batch::RunResult& r = runs.front();
    report_runs.push_back(
        {agent::toString(r.mode) + " (seed " + std::to_string(r.seed) + ")", r.summary, r.series, r.trajectories, ""});
  }
  monitor::ReportNotes notes;
  notes.title = "SWA batch report";
  notes.version = app::programVersion();
  notes.scenario = opt.scenario_path;
  for (int k = 0; k < opt.seeds; ++k) notes.seeds.push_back(scenario.seed + static_cast<std::uint64_t>(k));
  notes.scoring = record::scoringOf(scenario).metrics;  // r, and a mission's plan for the top-down plot
  notes.gnss_loss_s = sim::driftWindowStart(scenario) > 0.0 ? sim::driftWindowStart(scenario) : monitor::kNaN;
  notes.extra.push_back({"plots", "first seed of each mode; summary.json has every seed and the aggregate"});
  monitor::writeReport((out / "report").string(), report_runs, notes);
  app::markRunDirectory(out, before);
  const double simulated = scenario.duration_s * opt.seeds * static_cast<double>(modes.size());
  std::printf("\n%.0f simulated s in %.2f s wall, %.2f s CPU (%.0fx real time per CPU second)\nwrote %s and %s\n",
              simulated, wall, cpu, simulated / std::max(cpu, 1e-9), (out / "summary.json").c_str(),
              (out / "report" / "report.html").c_str());
  return 0;
}

// swa_batch --sweep / --shard as a process role.
class Study : public app::Role {
 public:
  Study(batch::BatchOptions options, std::shared_ptr<const batch::PreparedStudy> study, int jobs)
      : opt_(std::move(options)), study_(std::move(study)), jobs_(jobs) {}
  int run() override { return batch::runStudy(opt_, *study_, jobs_, stop_); }
  void stop() override { stop_ = true; }

 private:
  const batch::BatchOptions opt_;
  const std::shared_ptr<const batch::PreparedStudy> study_;
  const int jobs_;
  std::atomic<bool> stop_{false};
};

app::Plan prepare(const std::vector<std::string>& args) {
  const batch::BatchOptions opt = batch::parseBatchOptions(args);
  if (auto done = app::printIf(opt.help, batch::batchUsage, opt.list_parameters, sim::describeScenarioParameters)) {
    return *done;
  }
  if (opt.merge) return app::exitWith(batch::runMerge(opt));
  const study::StudySection section = study::readStudySection(opt.scenario_path);
  if (opt.study() || section.present) {
    if (opt.compare) {
      throw std::invalid_argument("--compare is not for studies (" + opt.scenario_path +
                                  " has a study section): sweep agent.mode instead");
    }
    auto study = std::make_shared<const batch::PreparedStudy>(batch::prepareStudy(opt, section));
    if (opt.dry_run) {
      batch::printStudyPlan(*study);
      return app::exitWith(0);
    }
    study::refuseOldStudy(opt.out_dir);  // before hours of runs, not after
    // A study uses every core unless told otherwise.
    const int jobs = opt.jobs_given ? opt.jobs : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    monitor::prepareOutputDir(opt.out_dir);
    return app::startWith(
        [opt, study, jobs]() -> std::unique_ptr<app::Role> { return std::make_unique<Study>(opt, study, jobs); });
  }
  const sim::Scenario scenario = sim::loadScenario(opt.scenario_path, opt.overrides);
  if (opt.dry_run) {
    std::printf("scenario %s: %d UAVs, %.0f s, seeds %llu..%llu\n", opt.scenario_path.c_str(), scenario.uav_count,
                scenario.duration_s, static_cast<unsigned long long>(scenario.seed),
                static_cast<unsigned long long>(scenario.seed + static_cast<std::uint64_t>(opt.seeds) - 1));
    return app::exitWith(0);
  }
  monitor::prepareOutputDir(opt.out_dir);  // before hours of seeds, not after
  return app::startWith(
      [opt, scenario]() -> std::unique_ptr<app::Role> { return std::make_unique<Batch>(opt, scenario); });
}

}  // namespace

int main(int argc, char** argv) { return app::runProgram("swa_batch", "scenario", argc, argv, prepare); }
