#include "live_mode.h"

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "live_record.h"
#include "swa/app/cpu_time.h"
#include "swa/app/version.h"
#include "swa/dds/options.h"
#include "swa/monitor/report_html.h"
#include "swa/run_record/restarts.h"
#include "swa/run_record/run_dir.h"
#include "swa/run_record/run_report.h"
#include "swa/sim/scenario_io.h"

namespace swa::monitor_node {
namespace {

int writeOutputs(const std::string& dir, const RunRecord& run) {
  try {
    record::writeRunFiles(dir, run);
    monitor::ReportNotes notes = record::reportNotes({run}, "SWA monitor report — " + run.label);
    notes.version = app::programVersion();
    const std::vector<std::string> written = monitor::writeReport(dir, record::reportRuns({run}), notes);
    std::printf("swa_monitor: %s\n", record::verdictText(run.verdict).c_str());
    std::printf("swa_monitor: report %s\n", written.front().c_str());
    return record::exitCode(run.verdict.outcome);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "swa_monitor: %s\n", e.what());
    std::printf("swa_monitor: %s (outputs incomplete)\n", record::verdictText(run.verdict).c_str());
    return kExitIncomplete;
  }
}

}  // namespace

LiveMode::LiveMode(const MonitorOptions& options, const std::optional<sim::Scenario>& scenario,
                   const LiveRunConfig& config, int domain_id)
    : options_(options), scenario_(scenario), config_(config), run_(config_) {
  MonitorNodeOptions node_options;
  if (scenario_) node_options.uav_count = scenario_->uav_count;
  node_options.formation = config_.metrics.formation;
  node_options.timeout_s = options_.timeout_s;
  node_options.quiet = options_.quiet;
  if (!options_.record_path.empty()) {
    recording_ = std::make_unique<recording::Recording>(options_.record_path, recording::Recording::Options{});
    metrics_ = std::make_unique<MetricsRecorder>(*recording_);
    node_options.recording = recording_.get();
    node_options.metrics = metrics_.get();
    node_options.record_set = options_.record_set;
    recording_->writeMetadata(recording::kRecordingMetadata,
                              {{recording::kRecordSetKey, recording::toString(options_.record_set)}});
    if (scenario_) {
      recording_->writeMetadata(
          recording::kScenarioMetadata,
          {{recording::kScenarioYamlKey, sim::scenarioToYaml(*scenario_)}, {"source", options_.scenario_path}});
    }
  }
  if (options_.live_address) {
    live_ = std::make_unique<live::LiveView>(*options_.live_address, options_.live_port, config_.metrics);
    const std::string host = options_.live_address->find(':') != std::string::npos ? "[" + *options_.live_address + "]"
                             : *options_.live_address == "0.0.0.0"                 ? std::string("127.0.0.1")
                                                                                   : *options_.live_address;
    std::fprintf(stderr, "swa_monitor: live view at http://%s:%d/ (Foxglove: ws://%s:%d)\n", host.c_str(),
                 live_->port(), host.c_str(), live_->port());
    node_options.live = live_.get();
  }
  node_ = std::make_unique<MonitorNode>(run_, node_options, domain_id, dds::resolveProfilesFile());
}

int LiveMode::run() {
  RunEnd end;
  try {
    end = node_->run();
  } catch (const std::exception& e) {
    end = {false, std::string("monitor error: ") + e.what()};
    std::fprintf(stderr, "swa_monitor: %s\n", end.reason.c_str());
  }
  node_.reset();  // every DDS entity deleted here: no more input

  run_.finish();
  finishRecording();
  finishLiveView();
  RunContext context;
  context.label = options_.label;
  context.scenario = options_.scenario_path;
  if (scenario_) context.seed = scenario_->seed;
  context.tolerance = options_.tolerance;
  context.end = end;
  if (!options_.restarts_path.empty()) context.restarts = record::readRestartLog(options_.restarts_path);
  const int status = writeOutputs(options_.out_dir, makeRunRecord(run_, config_, context));
  // The whole process's CPU time: what the recording and the live view cost is measured on it (BENCHMARKS.md).
  std::fprintf(stderr, "%s\n", app::cpuTimeLine("swa_monitor").c_str());
  return status;
}

void LiveMode::finishLiveView() {
  if (!live_) return;
  live_->onMetrics(run_.series());  // the steps finish() scored
  live_->flush();
  const live::LiveServer::Stats s = live_->stats();
  std::fprintf(stderr,
               "swa_monitor: live view: %llu page request(s), %llu client(s) (%llu refused), %llu message(s) sent, "
               "%llu dropped for clients that could not keep up\n",
               static_cast<unsigned long long>(s.pages), static_cast<unsigned long long>(s.connections),
               static_cast<unsigned long long>(s.refused), static_cast<unsigned long long>(s.sent),
               static_cast<unsigned long long>(s.dropped));
}

void LiveMode::finishRecording() {
  if (!recording_) return;
  try {
    metrics_->writeNew(run_.series());  // the steps finish() scored
    recording_->close();
    recording::writeRecordingManifest(options_.out_dir + "/recording.json", *recording_);
    std::uint64_t messages = 0;
    const auto channels = recording_->channelCounts();
    for (const auto& c : channels) messages += c.messages;
    std::printf("swa_monitor: recorded %llu messages on %zu channels into %s\n",
                static_cast<unsigned long long>(messages), channels.size(), recording_->path().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "swa_monitor: the recording %s is incomplete: %s\n", options_.record_path.c_str(), e.what());
  }
}

}  // namespace swa::monitor_node
