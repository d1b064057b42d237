#pragma once
// The monitor as a Fast DDS node: a thin adapter around LiveRun (live_run.h). Reads swa/truth, swa/events and
// swa/uav<i>/state, hands every sample to one worker thread (the listeners only push into a queue), converts it
// and feeds the LiveRun, prints the status line, and decides when the run has ended. No metric is computed here.

#include <atomic>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <variant>

#include <swa/msg/AgentState.h>
#include <swa/msg/ScenarioEvent.h>
#include <swa/msg/SwarmMission.h>
#include <swa/msg/SwarmTruth.h>

#include "live_record.h"
#include "live_run.h"
#include "live_view.h"
#include "recording_taps.h"
#include "status_line.h"
#include "step_metrics_json.h"
#include "swa/agent/config.h"
#include "swa/dds/command_gate.h"
#include "swa/dds/deaf_port_watch.h"
#include "swa/dds/handshake_watch.h"
#include "swa/dds/participant.h"
#include "swa/dds/sample_queue.h"
#include "swa/recording/record_set.h"
#include "swa/recording/recording.h"

namespace swa::monitor_node {

struct MonitorNodeOptions {
  std::optional<int> uav_count;      // state readers for UAVs 0..N-1; nullopt: for the ids of the first truth sample
  agent::FormationConfig formation;  // what the agents' states are scored with (LiveRunConfig::formation)
  double timeout_s = 0.0;            // wall seconds without EVENT_SCENARIO_END before giving up; 0 = never
  bool quiet = false;
  // Where every payload read also goes (swa_monitor --record); nullptr: no recording. Must outlive the node.
  recording::Recording* recording = nullptr;
  // kMonitor: only the monitor's own inputs go into `recording`, no reader is created just to record.
  recording::RecordSet record_set = recording::RecordSet::kAll;
  MetricsRecorder* metrics = nullptr;  // with `recording`: the monitor's metrics channel of it
  live::LiveView* live = nullptr;      // swa_monitor --live; nullptr: none. Must outlive the node.
  // After EVENT_SCENARIO_END, wall seconds to wait for the truth samples and states of the last steps (they travel
  // on other topics and may arrive after the event).
  double end_grace_s = 3.0;
};

class MonitorNode {
 public:
  // Creates the participant "swa_monitor" and its readers; throws swa::dds::DdsError. `run` must outlive the node.
  MonitorNode(LiveRun& run, const MonitorNodeOptions& options, int domain_id, const std::string& profiles_file);
  ~MonitorNode();
  MonitorNode(const MonitorNode&) = delete;
  MonitorNode& operator=(const MonitorNode&) = delete;

  // Feeds the LiveRun until the end event (plus the grace), stop(), or the timeout. Does not call finish().
  RunEnd run();
  void stop() { stop_requested_ = true; }
  // Samples of the monitor's topics that did not decode (dropped).
  std::uint64_t undecodable() const { return undecodable_; }

 private:
  struct StateInput {
    int topic_uav = 0;
    msg::AgentState state;
  };
  struct MissionInput {
    dds::WriterGuid writer{};
    msg::SwarmMission mission;
  };
  using Input = std::variant<msg::SwarmTruth, StateInput, msg::ScenarioEvent, MissionInput>;

  void connect();                    // the participant and every reader (again after a stalled secure handshake)
  void createRunReaders();           // swa/events and swa/truth
  void createRunReadersWhenReady();  // ... once every agent's state writer is matched
  void subscribeState(int uav);
  void createStateReader(int uav);
  void reconnectIfHandshakeStalled();
  // A shared-memory port of its own re-created under it by a peer (deaf_port_watch.h): nothing more would reach it,
  // and the recording would stop while the run goes on.
  void reconnectIfDeaf();
  void process(Input& input);
  void processMission(const MissionInput& input);
  void showStatus(double wall_s, bool last);
  // A raw reader of `topic` whose payloads are recorded (if recording) and decoded into `push`.
  template <class PubSubType, class Push>
  dds::Reader<dds::Payload> readAndRecord(const std::string& topic, const char* profile, Push push);
  void publishNewMetrics();  // to the recording and the live view
  // Whether readers are created only to record (recording every topic).
  bool recordsEveryTopic() const {
    return options_.recording != nullptr && options_.record_set == recording::RecordSet::kAll;
  }

  LiveRun& run_;
  MonitorNodeOptions options_;
  StatusPacer pacer_;
  std::size_t status_width_ = 0;  // length of the line last shown in place (to blank its rest)
  std::set<int> state_readers_;
  bool readers_from_truth_pending_ = false;
  const int domain_id_;
  const std::string profiles_file_;
  bool truth_seen_ = false;
  std::chrono::steady_clock::time_point connected_at_;
  dds::HandshakeWatch handshake_;
  dds::DeafPortWatch deaf_ports_;
  std::atomic<bool> stop_requested_{false};
  std::atomic<std::uint64_t> undecodable_{0};
  // The ground's mission, through the agents' rule (agent_node.h): one writer, until its participant leaves; the
  // command in force sent again to a re-created reader is not a new one.
  dds::CommandGate mission_gate_;
  std::optional<dds::WriterGuid> mission_writer_;
  std::uint32_t mission_seq_ = 0;

  // The queue outlives the participant, whose listeners push into it.
  dds::SampleQueue<Input> queue_;
  std::unique_ptr<dds::Participant> participant_;
  dds::Reader<dds::Payload> truth_reader_;
  dds::Reader<msg::SwarmMission> mission_reader_;
  std::map<int, dds::Reader<dds::Payload>> state_reader_handles_;
  std::map<int, recording::UavTaps> uav_taps_;  // --record: each UAV's commands and sensors (recording_taps.h)
  bool run_readers_pending_ = false;
  std::optional<std::chrono::steady_clock::time_point> all_matched_at_;  // recording: every reader matched since
};

}  // namespace swa::monitor_node
