#pragma once
// swa_monitor's live mode as a process role: the DDS node feeds a LiveRun until the end of the scenario (or stop());
// then, with every DDS entity deleted, the run is finished, judged and written to its directory (swa/run_record).

#include <memory>
#include <optional>

#include "live_run.h"
#include "monitor_node.h"
#include "monitor_options.h"
#include "step_metrics_json.h"
#include "swa/app/program.h"
#include "swa/recording/recording.h"
#include "swa/sim/scenario.h"

namespace swa::monitor_node {

class LiveMode : public app::Role {
 public:
  // Creates the DDS node; throws swa::dds::DdsError.
  LiveMode(const MonitorOptions& options, const std::optional<sim::Scenario>& scenario, const LiveRunConfig& config,
           int domain_id);

  // The verdict's exit status (0 PASS, 1 FAIL, 3 INCOMPLETE).
  int run() override;
  void stop() override { node_->stop(); }

 private:
  void finishRecording();
  void finishLiveView();

  const MonitorOptions options_;
  const std::optional<sim::Scenario> scenario_;
  const LiveRunConfig config_;
  LiveRun run_;
  // --record: declared before the node, which writes into them from DDS threads until it is destroyed.
  std::unique_ptr<recording::Recording> recording_;
  std::unique_ptr<MetricsRecorder> metrics_;
  std::unique_ptr<live::LiveView> live_;
  std::unique_ptr<MonitorNode> node_;
};

}  // namespace swa::monitor_node
