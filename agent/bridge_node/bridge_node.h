#pragma once
// swa_px4_bridge as a Fast DDS node: a thin adapter around swa::autopilot::BridgeCore (swa/autopilot/bridge_core.h has
// the rules) with one VehicleLink for the autopilot's side (vehicle_link.h: PX4 or ArduPilot). The vehicle's samples
// and the agent's commands are handled in the listener that delivers them, under one mutex (as the agent node does:
// no worker thread between the sample and its answer); run() ticks the core every 10 ms for the heartbeat and the
// stale / lost rules, publishes the diagnostics, and watches for a twin.
// Attitude is forwarded only once the vehicle reads our command stream (its readers matched): an answer written
// before that would be lost (best effort, volatile), and the lockstep simulator would wait for it. The newest sample
// that came earlier is kept and forwarded then.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include <swa/msg/AgentState.h>
#include <swa/msg/BridgeState.h>
#include <swa/msg/GnssFix.h>
#include <swa/msg/Imu.h>
#include <swa/msg/VelocitySetpoint.h>

#include "bridge_options.h"
#include "swa/app/log_histogram.h"
#include "swa/app/program.h"
#include "swa/autopilot/bridge_core.h"
#include "swa/autopilot/odometry_feed.h"
#include "swa/dds/command_gate.h"
#include "swa/dds/deaf_port_watch.h"
#include "swa/dds/handshake_watch.h"
#include "swa/dds/participant.h"
#include "vehicle_link.h"

namespace swa::bridge_node {

class BridgeNode : public app::Role {
 public:
  static constexpr int kExitTwin = 3;

  // Creates every DDS entity; throws swa::dds::DdsError.
  BridgeNode(const BridgeOptions& options, int domain_id, const std::string& profiles_file);
  ~BridgeNode() override;

  int run() override;
  void stop() override { stop_requested_ = true; }

 private:
  struct Attitude {
    std::uint64_t timestamp_us = 0;
    px4::Quaternion q;
    std::optional<ardupilot::SpecificForce> force_frd;
  };

  void connect();  // creates the participant, the agent's endpoints and the vehicle's
  // Deletes the participant. Listeners still running on it (they call participant_, imu_, ...) see it gone under
  // mutex_ and return; a plain participant_.reset() would null the pointer while they still ran.
  void closeParticipant();
  void reconnect();  // a new participant (a stalled DDS Security handshake): closeParticipant, then connect
  double nowS() const;
  // From the vehicle link's listeners.
  void onAttitude(const Attitude& a);
  void onStatus(bool armed, std::uint8_t mode);
  void onGnss(const agent::GnssSample& g);
  void onVehicleLog(const std::string& line);
  void onEstimator(bool unaided);
  // From the agent's state reader: its estimate as the vehicle's external odometry (odometry_feed.h).
  void onAgentState(msg::AgentState&& m);
  void onCommand(msg::VelocitySetpoint&& m, const dds::WriterGuid& writer);
  // With mutex_ held.
  void forward(const Attitude& a, std::chrono::steady_clock::time_point received);
  void report();  // the core's events to the log, and a state message when there were any (or a second passed)
  void logFinalCounts() const;
  void logGnssCounts(const px4::GnssForwardCounters& g) const;
  void writeSummary() const;  // --summary-out

  // When an attitude sample came in and its IMU sample went out, to time the answer's way back (the bridge's hop).
  struct Timing {
    std::uint64_t timestamp_us = 0;
    std::chrono::steady_clock::time_point in, imu_out;
  };

  const int id_;
  const BridgeOptions options_;
  const int domain_id_;
  const std::string profiles_file_;
  const std::chrono::steady_clock::time_point started_;
  // The newest participant's creation (connect): the vehicle gets 5 s from it to read the commands before the bridge
  // says what it waits for, once per participant (a re-created one is matched again from nothing).
  std::chrono::steady_clock::time_point connected_at_;
  bool waiting_reported_ = false;
  const std::unique_ptr<VehicleLink> vehicle_;

  std::mutex mutex_;  // guards everything below but the DDS handles
  autopilot::BridgeCore core_;
  std::uint32_t gnss_seq_ = 0;
  bool gnss_reported_ = false, last_gnss_valid_ = false;
  dds::CommandGate gate_;
  std::optional<Attitude> pending_;          // before the vehicle reads our stream
  std::optional<Attitude> newest_attitude_;  // the vehicle's clock and attitude for the odometry
  autopilot::OdometryFeed odometry_;
  std::optional<std::uint64_t> feeding_since_us_;  // vehicle time the feed last started
  bool not_fusing_reported_ = false;
  std::chrono::steady_clock::time_point pending_at_{};
  bool vehicle_reads_ = false;
  bool status_seen_ = false;
  bool upside_down_reported_ = false;
  std::uint32_t imu_seq_ = 0, state_seq_ = 0;
  std::optional<msg::Imu> last_imu_;  // the newest forwarded: written again by a new participant (reconnect)
  std::optional<autopilot::Setpoint> last_answer_;  // the newest setpoint sent: again if the vehicle repeats its sample
  std::uint64_t answers_repeated_ = 0;
  std::uint64_t commands_foreign_ = 0;  // naming another UAV
  std::string last_event_;
  std::deque<Timing> timings_;  // the newest samples forwarded
  // Per answered sample: attitude in -> setpoint out (the loop as the vehicle sees it), IMU out -> command in (the
  // agent's loop, as the direct interface has it), and the difference (what the bridge adds).
  app::LogHistogram hop_, agent_loop_, bridge_part_;
  std::chrono::steady_clock::time_point last_state_{};
  std::atomic<bool> stop_requested_{false};
  dds::HandshakeWatch handshake_;
  // With --engage and security: the requests' endpoints can stall alone, after the stream runs (measured: GUIDED 10
  // to 17 s late in 2 of 5 secure launches through ArduPilot). Until the vehicle is engaged a new participant costs
  // nothing (the vehicle does not follow the stream yet), so the same policy applies to them up to then.
  dds::HandshakeWatch requests_handshake_;
  // A shared-memory port of its own re-created under it by a peer: nothing from the vehicle or the agent arrives, even
  // before the first sample (deaf_port_watch.h).
  dds::DeafPortWatch deaf_ports_;
  // Once armed and in the control mode (PX4: offboard; ArduPilot: GUIDED): a pilot taking over later is no reason to
  // re-create the participant in flight.
  std::atomic<bool> engaged_{false};

  std::unique_ptr<dds::Participant> participant_;  // written by the main thread under mutex_; null while closing
  dds::Writer<msg::Imu> imu_;
  dds::Writer<msg::BridgeState> state_;
  dds::Writer<msg::GnssFix> gnss_;  // not with --no-gnss
  dds::Reader<msg::VelocitySetpoint> cmd_reader_;
  dds::Reader<msg::AgentState> state_reader_;  // not with --odometry off
};

}  // namespace swa::bridge_node
