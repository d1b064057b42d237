#pragma once
// The agent of one UAV as a Fast DDS node: a thin adapter around swa::agent::Agent. Reads only
// swa/uav<id>/{imu,detections,gnss,sensors}, writes only swa/uav<id>/{cmd_vel,state}. Samples are processed one at a
// time, in stamp order (sample_order.h), in the listener that delivers them: handing them to a worker thread cost one
// more thread wake-up per sample, which with 8 agents on 2 vCPUs added ~35 % to the sensor-to-command latency
// (BENCHMARKS.md). Fast DDS delivers one transport port's samples on one receive thread; a mutex serialises the
// processing should samples come in through two (e.g. shared memory and UDP). Per sample the agent:
//   - one VelocitySetpoint per IMU sample, echoing the IMU's stamp and seq (the lockstep simulator waits for it), and
//     in the ros2 naming the same command as a geometry_msgs/TwistStamped on swa/uav<id>/cmd_vel_stamped;
//   - an AgentState whenever the sample time crosses a 100 ms boundary (10 Hz of sim time, deterministic);
//   - and, once the agent has run, an AgentState at least every second of wall time whatever the inputs do: the
//     state never goes silent while the process lives, and says STAGE_NO_INPUT after a second without a valid IMU
//     sample (a rejected sample gets no command, so the autopilot's offboard timeout is what holds the UAV).

#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <variant>

#include <swa/msg/AgentState.h>
#include <swa/msg/Clock.h>
#include <swa/msg/Detections.h>
#include <swa/msg/GnssFix.h>
#include <swa/msg/Imu.h>
#include <swa/msg/SensorFrame.h>
#include <swa/msg/SwarmMission.h>
#include <swa/msg/VelocitySetpoint.h>
#include <swa/ros/Detection3DArray.h>
#include <swa/ros/PoseWithCovarianceArrayStamped.h>
#include <swa/ros/TwistStamped.h>

#include "redelivery_filter.h"
#include "sample_order.h"
#include "silence_watch.h"
#include "swa/agent/agent.h"
#include "swa/agent/detection_adapter.h"
#include "swa/app/program.h"
#include "swa/app/stall_watch.h"
#include "swa/dds/command_gate.h"
#include "swa/dds/deaf_port_watch.h"
#include "swa/dds/handshake_watch.h"
#include "swa/dds/participant.h"
#include "swa/wire/agent_feed.h"
#include "world_pause.h"

namespace swa::agent_node {

struct AgentNodeStats {
  std::uint64_t imu = 0, detections = 0, gnss = 0;
  std::uint64_t commands = 0, states = 0;
  std::uint64_t foreign = 0;  // samples naming another UAV (a wiring error upstream): dropped
  std::uint64_t write_failures = 0;
  std::uint64_t forced_releases = 0;  // samples the stamp orderer let through early (sample_order.h)
  std::uint64_t replayed = 0;         // history sent again to a re-created participant, dropped (redelivery_filter.h)
  // Missions from the ground (swa/swarm/mission): received; refused as a second writer's; unreadable (an unknown
  // kind); the newest one sent again to a re-created reader, dropped. The agent counts those it cannot fly.
  std::uint64_t missions = 0, missions_other_writer = 0, missions_unreadable = 0, missions_replayed = 0;
};

class AgentNode : public app::Role {
 public:
  // run()'s status when an older agent with this id runs in the same swarm (peer_book.h).
  static constexpr int kExitTwin = 3;
  // No IMU sample this long from a matched writer while the agent runs: a channel is broken, the participant is
  // re-created (silence_watch.h). Longer than the DDS lease (4 s), so that a writer that died or was stopped is
  // forgotten first.
  static constexpr std::chrono::seconds kSilentLimit{6};
  // Two polls of run() further apart than this: the process itself did not run (SIGSTOP, a starved host), and what it
  // did not hear meanwhile says nothing about its channels.
  static constexpr std::chrono::milliseconds kPollGapLimit{250};

  // Creates every DDS entity; throws swa::dds::DdsError.
  AgentNode(int uav_id, const agent::AgentConfig& config, int domain_id, const std::string& profiles_file);
  ~AgentNode() override;

  // Until stop(): publishes the pending state when the inputs go quiet. Then deletes the DDS entities, so no
  // listener runs any more and stats() / diagnostics() are final, and logs them. Returns the exit status.
  int run() override;
  void stop() override;
  const AgentNodeStats& stats() const { return stats_; }
  const agent::Diagnostics& diagnostics() const { return agent_.diagnostics(); }

 private:
  using Input = std::variant<msg::Imu, msg::Detections, msg::GnssFix>;

  void connect();                                         // creates the participant and the endpoints
  void onInput(Input&& in);                               // listener threads
  void onFrame(msg::SensorFrame&& frame);                 // listener threads: each part through onInput
  void onForeign(const agent::ForeignDetectionSet& set);  // listener threads: through adapter_, then onInput
  void onMission(msg::SwarmMission&& m, const dds::WriterGuid& writer);  // listener thread
  void reportMission();                 // handle(): a ground command the agent has just taken over
  std::string detectionsTopic() const;  // of sensor.input
  void handle(Input& in);
  void publishState(agent::StampNs stamp_ns, bool no_input = false);
  void heartbeat();  // run(): the wall-clock state
  void refuseAsTwin();
  // Matched remote endpoints of cmd_vel, imu, detections, gnss (queried outside mutex_, see run()).
  using Matched = std::array<int, 4>;
  Matched matchedNow() const;
  // Why the participant must be re-created after a peer came back from an expired lease, if it must.
  std::optional<std::string> endpointsLostAfterPeerReturn(const Matched& matched);
  void reportWaiting(const Matched& matched);  // once per connection: no IMU sample yet, and what has matched
  void noteYoungerTwins();
  void logFinalCounts() const;

  const int id_;
  const int domain_id_;
  const std::string profiles_file_;
  agent::Agent agent_;
  wire::AgentFeed feed_;             // agent_ fed the messages (guarded by mutex_)
  agent::DetectionAdapter adapter_;  // guarded by mutex_
  std::uint32_t foreign_seq_ = 0;    // guarded by mutex_
  StampOrderer<Input> order_;
  std::chrono::steady_clock::time_point started_;
  AgentNodeStats stats_;
  std::uint32_t state_seq_ = 0;
  bool state_due_set_ = false;
  agent::StampNs next_state_ns_ = 0;
  // The state of a 100 ms boundary step is published once every sample of that step has been processed (before the
  // next step's IMU, or when the inputs go quiet), so it is the estimate the in-process loop scores at that step.
  std::optional<agent::StampNs> pending_state_ns_;

  std::mutex mutex_;  // guards everything above; held while a sample is processed
  std::chrono::steady_clock::time_point last_input_;
  std::chrono::steady_clock::time_point last_state_;      // wall time of the last published state
  std::chrono::steady_clock::time_point last_fresh_imu_;  // wall time of the last accepted IMU sample
  bool had_fresh_imu_ = false;
  dds::HandshakeWatch handshake_;
  int reconnects_ = 0;
  std::atomic<bool> stop_requested_{false};
  std::condition_variable wake_;  // run()'s wait: stop(), or its next deadline
  int peers_back_ = 0;            // PeerBook count of the current participant
  std::optional<std::chrono::steady_clock::time_point> peer_back_at_;
  std::string peer_back_name_;
  dds::PeerKey peer_back_key_{};
  // Which of our endpoints (cmd_vel, imu, detections, gnss) have matched since connect(): only those can be lost, and
  // a detection source matched is part of a start (the handshake watch in run()).
  std::array<bool, 4> matched_once_{};
  std::chrono::steady_clock::time_point connected_at_;
  bool waiting_reported_ = false;
  ReplayFilter replay_;
  std::optional<msg::VelocitySetpoint> last_cmd_;  // sent again after a reconnection
  // No IMU sample for kSilentLimit while their writer is matched: a channel is broken (silence_watch.h).
  SilenceWatch imu_silence_{kSilentLimit};
  std::optional<std::chrono::steady_clock::time_point> last_imu_at_;  // wall time of the last IMU sample let in
  // The same for SWA's own detections, watched while the IMU flows (agent_node.cpp).
  SilenceWatch detections_silence_{kSilentLimit};
  // A shared-memory port of its own re-created under it by a peer: nothing sent to it arrives, even before the first
  // sample, where the silence watches cannot tell (deaf_port_watch.h).
  dds::DeafPortWatch deaf_ports_;
  WorldPause world_pause_;  // a lockstep simulator waiting for someone: silence owes nothing (world_pause.h)
  std::optional<std::chrono::steady_clock::time_point> last_detections_at_;
  app::StallWatch own_stall_{kPollGapLimit};  // whether run()'s polls come as often as they should

  // One writer of the ground's mission: the first heard from, until its participant leaves (a ground tool that
  // exits, or whose lease expires): silence is no handover, a ground station speaks only when the operator does.
  dds::CommandGate mission_gate_;
  std::optional<dds::WriterGuid> mission_writer_;  // the newest command's writer and number: a re-created reader is
  std::uint32_t mission_seq_ = 0;                  // sent it again, which must not be flown twice
  std::uint64_t missions_flown_ = 0;               // the agent's count when the last was reported
  agent::StampNs last_imu_stamp_ = 0;              // of the newest IMU sample handled
  agent::StampNs mission_arrived_after_ns_ = 0;    // last_imu_stamp_ when the pending command arrived

  std::unique_ptr<dds::Participant> participant_;
  dds::Writer<msg::VelocitySetpoint> cmd_writer_;
  dds::Writer<geometry_msgs::msg::TwistStamped> twist_writer_;  // the ros2 naming only: cmd_vel as a standard type
  dds::Writer<msg::AgentState> state_writer_;
  dds::Reader<msg::Imu> imu_reader_;
  dds::Reader<msg::Detections> det_reader_;  // sensor.input = swa
  // sensor.input = vision_msgs or uvdar: read, converted by adapter_ (under mutex_) and handled as SWA's own.
  dds::Reader<vision_msgs::msg::Detection3DArray> vision_reader_;
  dds::Reader<mrs_msgs::msg::PoseWithCovarianceArrayStamped> uvdar_reader_;
  dds::Reader<msg::GnssFix> gnss_reader_;
  // sensor.input = swa in the SWA naming: the simulator's frames (a step's samples in one message), unpacked into
  // the three inputs above.
  dds::Reader<msg::SensorFrame> frame_reader_;
  dds::Reader<msg::SwarmMission> mission_reader_;
  dds::Reader<msg::Clock> clock_reader_;  // only to tell a waiting lockstep run (world_pause.h)
};

}  // namespace swa::agent_node
