#include "combine.h"

#include <filesystem>
#include <fstream>
#include <optional>
#include <system_error>

#include "swa/app/version.h"
#include "swa/run_record/run_dir.h"
#include "swa/run_record/run_report.h"
#include "swa/run_record/scoring.h"
#include "swa/sim/scenario_io.h"

namespace swa::monitor_node {

int runCombine(const MonitorOptions& options, std::ostream& out, std::ostream& err) {
  std::optional<sim::Scenario> scenario;
  std::vector<record::RunRecord> runs;
  record::Json list = record::Json::array();
  try {
    if (!options.scenario_path.empty()) scenario = sim::loadScenario(options.scenario_path, options.overrides);
    for (const CombineInput& input : options.combine) {
      record::LoadedRun loaded = record::readRunDir(input.dir);
      loaded.run.label = input.label;
      loaded.summary["label"] = input.label;
      list.push_back(std::move(loaded.summary));
      runs.push_back(std::move(loaded.run));
    }
  } catch (const params::ConfigError& e) {
    err << "swa_monitor: invalid scenario:\n" << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    err << "swa_monitor --combine: " << e.what() << "\n";
    return kExitBadInput;
  }

  monitor::ReportNotes notes = record::reportNotes(runs, "SWA monitor report — comparison");
  notes.version = app::programVersion();
  if (scenario) {
    notes.scenario = options.scenario_path;
    notes.scoring = record::scoringOf(*scenario).metrics;
    notes.gnss_loss_s = monitor::gnssLossTime(notes.scoring);
  }
  if (options.tolerance_given) notes.scoring.radius_tolerance = options.tolerance;

  namespace fs = std::filesystem;
  try {
    std::error_code ec;
    fs::create_directories(options.out_dir, ec);
    if (ec) throw std::runtime_error("cannot create " + options.out_dir + ": " + ec.message());
    record::writeTextFile((fs::path(options.out_dir) / record::kSummaryFile).string(),
                          record::jsonText(record::Json{{"runs", std::move(list)}}));
    const std::vector<std::string> written = monitor::writeReport(options.out_dir, record::reportRuns(runs), notes);
    for (const record::RunRecord& r : runs)
      out << "swa_monitor: " << r.label << ": " << record::verdictText(r.verdict) << "\n";
    out << "swa_monitor: report " << written.front() << "\n";
  } catch (const std::exception& e) {
    err << "swa_monitor --combine: " << e.what() << "\n";
    return kExitBadInput;
  }
  return record::exitCode(runs.front().verdict.outcome);
}

}  // namespace swa::monitor_node
