#pragma once
// swa_px4_bridge as a Fast DDS node: a thin adapter around swa::px4::BridgeCore (swa/px4/bridge_core.h has the rules).
// PX4's samples and the agent's commands are handled in the listener that delivers them, under one mutex (as the
// agent node does: no worker thread between the sample and its answer); run() ticks the core every 10 ms for the
// heartbeat and the stale / lost rules, publishes the diagnostics, and watches for a twin.
// Attitude is forwarded only once PX4 reads our trajectory_setpoint and offboard_control_mode (both matched): an answer
// written before that would be lost (best effort, volatile), and the lockstep simulator would wait for it. The newest
// sample that came earlier is kept and forwarded then.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include <swa/msg/BridgeState.h>
#include <swa/msg/GnssFix.h>
#include <swa/msg/Imu.h>
#include <swa/msg/VelocitySetpoint.h>
#include <swa/px4/OffboardControlMode_v1_15.h>
#include <swa/px4/SensorGps_v1_15.h>
#include <swa/px4/SensorGps_v1_17.h>
#include <swa/px4/TrajectorySetpoint_v1_15.h>
#include <swa/px4/VehicleAttitude_v1_15.h>
#include <swa/px4/VehicleCommandAck_v1_15.h>
#include <swa/px4/VehicleCommand_v1_15.h>
#include <swa/px4/VehicleLocalPosition_v1_15.h>
#include <swa/px4/VehicleLocalPosition_v1_16.h>
#include <swa/px4/VehicleStatus_v1_15.h>
#include <swa/px4/VehicleStatus_v1_16.h>

#include "bridge_options.h"
#include "swa/app/log_histogram.h"
#include "swa/app/program.h"
#include "swa/dds/command_gate.h"
#include "swa/dds/handshake_watch.h"
#include "swa/dds/participant.h"
#include "swa/px4/bridge_core.h"
#include "swa/px4/gnss.h"

namespace swa::px4_bridge {

class BridgeNode : public app::Role {
 public:
  static constexpr int kExitTwin = 3;

  // Creates every DDS entity; throws swa::dds::DdsError.
  BridgeNode(const BridgeOptions& options, int domain_id, const std::string& profiles_file);
  ~BridgeNode() override;

  int run() override;
  void stop() override { stop_requested_ = true; }

 private:
  void connect();  // creates the participant and the endpoints
  double nowS() const;
  void onAttitude(px4_msgs::msg::VehicleAttitude&& m);
  void onStatus(std::uint8_t arming_state, std::uint8_t nav_state);
  void onGps(const px4::GpsReport& gps);
  void onLocalPosition(const px4::LocalPositionReport& position);
  void connectGnss(dds::Participant& p);  // the readers of PX4's fix and position, the writer of swa/uav<I>/gnss
  void onAck(px4_msgs::msg::VehicleCommandAck&& m);
  void onCommand(msg::VelocitySetpoint&& m, const dds::WriterGuid& writer);
  // With mutex_ held.
  void forward(const px4_msgs::msg::VehicleAttitude& m, std::chrono::steady_clock::time_point received);
  void send(const px4::Outbox& out);
  void report();  // the core's events to the log, and a state message when there were any (or a second passed)
  void logFinalCounts() const;
  void writeSummary() const;  // --summary-out

  // When an attitude sample came in and its IMU sample went out, to time the answer's way back (the bridge's hop).
  struct Timing {
    std::uint64_t timestamp_us = 0;
    std::chrono::steady_clock::time_point in, imu_out;
  };

  const int id_;
  const std::string ns_;
  const std::string status_topic_;  // the release's name of vehicle_status
  const BridgeOptions options_;
  const int domain_id_;
  const std::string profiles_file_;
  const std::chrono::steady_clock::time_point started_;

  std::mutex mutex_;  // guards everything below but the DDS handles
  px4::BridgeCore core_;
  px4::GnssForward gnss_forward_;
  std::uint32_t gnss_seq_ = 0;
  bool gnss_reported_ = false, last_gnss_valid_ = false;
  dds::CommandGate gate_;
  std::optional<px4_msgs::msg::VehicleAttitude> pending_;  // before PX4 reads our stream
  std::chrono::steady_clock::time_point pending_at_{};
  bool px4_reads_ = false;
  bool status_seen_ = false;
  std::uint32_t imu_seq_ = 0, state_seq_ = 0;
  std::uint64_t commands_foreign_ = 0;  // naming another UAV
  std::string last_event_;
  std::deque<Timing> timings_;  // the newest samples forwarded
  // Per answered sample: attitude in -> setpoint out (the loop as PX4 sees it), IMU out -> command in (the agent's
  // loop, as the direct interface has it), and the difference (what the bridge adds).
  app::LogHistogram hop_, agent_loop_, bridge_part_;
  std::chrono::steady_clock::time_point last_state_{};
  std::atomic<bool> stop_requested_{false};
  dds::HandshakeWatch handshake_;

  std::unique_ptr<dds::Participant> participant_;
  dds::Writer<msg::Imu> imu_;
  dds::Writer<msg::BridgeState> state_;
  dds::Writer<msg::GnssFix> gnss_;  // not with --no-gnss
  dds::Writer<px4_msgs::msg::TrajectorySetpoint> setpoint_;
  dds::Writer<px4_msgs::msg::OffboardControlMode> offboard_;
  dds::Writer<px4_msgs::msg::VehicleCommand> vehicle_command_;
  dds::Reader<px4_msgs::msg::VehicleAttitude> attitude_reader_;
  dds::Reader<px4_msgs::msg::VehicleStatus> status_reader_;                // v1.15
  dds::Reader<px4_v1_16::px4_msgs::msg::VehicleStatus> status_reader_v1_16_;  // v1.16 and later
  dds::Reader<px4_msgs::msg::VehicleCommandAck> ack_reader_;
  dds::Reader<msg::VelocitySetpoint> cmd_reader_;
  // The release's layouts of PX4's fix and local position (one of each pair), not with --no-gnss.
  dds::Reader<px4_msgs::msg::SensorGps> gps_reader_;
  dds::Reader<px4_v1_17::px4_msgs::msg::SensorGps> gps_reader_v1_17_;
  dds::Reader<px4_msgs::msg::VehicleLocalPosition> position_reader_;
  dds::Reader<px4_v1_16::px4_msgs::msg::VehicleLocalPosition> position_reader_v1_16_;
};

}  // namespace swa::px4_bridge
