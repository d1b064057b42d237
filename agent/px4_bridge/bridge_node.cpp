#include "bridge_node.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>

#include <swa/msg/BridgeStatePubSubTypes.h>
#include <swa/msg/GnssFixPubSubTypes.h>
#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>
#include <swa/px4/OffboardControlMode_v1_15PubSubTypes.h>
#include <swa/px4/SensorGps_v1_15PubSubTypes.h>
#include <swa/px4/SensorGps_v1_17PubSubTypes.h>
#include <swa/px4/TrajectorySetpoint_v1_15PubSubTypes.h>
#include <swa/px4/VehicleAttitude_v1_15PubSubTypes.h>
#include <swa/px4/VehicleCommandAck_v1_15PubSubTypes.h>
#include <swa/px4/VehicleCommand_v1_15PubSubTypes.h>
#include <swa/px4/VehicleLocalPosition_v1_15PubSubTypes.h>
#include <swa/px4/VehicleLocalPosition_v1_16PubSubTypes.h>
#include <swa/px4/VehicleStatus_v1_15PubSubTypes.h>
#include <swa/px4/VehicleStatus_v1_16PubSubTypes.h>

#include "swa/app/signals.h"
#include "swa/dds/topics.h"
#include "swa/px4/release.h"
#include "swa/px4/vehicle.h"
#include "swa/wire/px4.h"
#include "swa/wire/samples.h"

namespace swa::px4_bridge {
namespace {

constexpr auto kTickPeriod = std::chrono::milliseconds(10);
constexpr auto kStatePeriod = std::chrono::seconds(1);
// cmd_vel's writer may change after this much silence (a restarted agent), as in the simulator (command_gate.h).
constexpr auto kCommandHandover = std::chrono::milliseconds(500);
// Samples whose timing is kept for their answer: a second at 100 Hz, far more than an answer takes.
constexpr std::size_t kTimedSamples = 128;

namespace topics = dds::topics;

// The Participant validates the deployment environment; here only whether security is on matters.
bool isSecure() {
  const char* dir = std::getenv("SWA_SECURITY_DIR");
  return dir != nullptr && *dir != '\0';
}

}  // namespace

BridgeNode::BridgeNode(const BridgeOptions& options, int domain_id, const std::string& profiles_file)
    : id_(options.id),
      ns_(px4Namespace(options)),
      status_topic_(px4::topicName(options.px4_release, "vehicle_status")),
      options_(options),
      domain_id_(domain_id),
      profiles_file_(profiles_file),
      started_(std::chrono::steady_clock::now()),
      core_(options.core),
      gate_(1, kCommandHandover),
      handshake_(isSecure()) {
  connect();
}

void BridgeNode::connect() {
  participant_ = std::make_unique<dds::Participant>("swa_bridge_" + std::to_string(id_), domain_id_, profiles_file_);
  handshake_.connected(std::chrono::steady_clock::now());
  dds::Participant& p = *participant_;
  imu_ = p.writer<msg::ImuPubSubType>(topics::imu(id_), "swa_sensor_writer");
  state_ = p.writer<msg::BridgeStatePubSubType>(topics::bridgeState(id_), "swa_state_writer");
  setpoint_ = p.writer<px4_msgs::msg::TrajectorySetpointPubSubType>(topics::px4In(ns_, "trajectory_setpoint"),
                                                                      "px4_in_writer");
  offboard_ = p.writer<px4_msgs::msg::OffboardControlModePubSubType>(topics::px4In(ns_, "offboard_control_mode"),
                                                                       "px4_in_writer");
  if (options_.core.engage) {
    vehicle_command_ =
        p.writer<px4_msgs::msg::VehicleCommandPubSubType>(topics::px4In(ns_, "vehicle_command"), "px4_in_writer");
  }
  if (px4::hasV116VehicleStatus(options_.px4_release)) {
    status_reader_v1_16_ = p.reader<px4_v1_16::px4_msgs::msg::VehicleStatusPubSubType>(
        topics::px4Out(ns_, status_topic_), "px4_out_reader",
        [this](px4_v1_16::px4_msgs::msg::VehicleStatus&& m) { onStatus(m.arming_state(), m.nav_state()); });
  } else {
    status_reader_ = p.reader<px4_msgs::msg::VehicleStatusPubSubType>(
        topics::px4Out(ns_, status_topic_), "px4_out_reader",
        [this](px4_msgs::msg::VehicleStatus&& m) { onStatus(m.arming_state(), m.nav_state()); });
  }
  ack_reader_ = p.reader<px4_msgs::msg::VehicleCommandAckPubSubType>(
      topics::px4Out(ns_, "vehicle_command_ack"), "px4_out_reader",
      [this](px4_msgs::msg::VehicleCommandAck&& m) { onAck(std::move(m)); });
  cmd_reader_ = p.readerWithOrigin<msg::VelocitySetpointPubSubType>(
      topics::cmdVel(id_), "swa_command_reader",
      [this](msg::VelocitySetpoint&& m, const dds::WriterGuid& w) { onCommand(std::move(m), w); });
  if (!options_.no_gnss) connectGnss(p);
  attitude_reader_ = p.reader<px4_msgs::msg::VehicleAttitudePubSubType>(
      topics::px4Out(ns_, "vehicle_attitude"), "px4_out_reader",
      [this](px4_msgs::msg::VehicleAttitude&& m) { onAttitude(std::move(m)); });
}

void BridgeNode::connectGnss(dds::Participant& p) {
  gnss_ = p.writer<msg::GnssFixPubSubType>(topics::gnss(id_), "swa_detections_gnss_writer");
  const px4::Release r = options_.px4_release;
  const std::string gps_topic = topics::px4Out(ns_, px4::topicName(r, "vehicle_gps_position"));
  const std::string position_topic = topics::px4Out(ns_, px4::topicName(r, "vehicle_local_position"));
  if (px4::hasV117SensorGps(r)) {
    gps_reader_v1_17_ = p.reader<px4_v1_17::px4_msgs::msg::SensorGpsPubSubType>(
        gps_topic, "px4_out_reader",
        [this](px4_v1_17::px4_msgs::msg::SensorGps&& m) { onGps(wire::gpsReportOf(m)); });
  } else {
    gps_reader_ = p.reader<px4_msgs::msg::SensorGpsPubSubType>(
        gps_topic, "px4_out_reader", [this](px4_msgs::msg::SensorGps&& m) { onGps(wire::gpsReportOf(m)); });
  }
  if (px4::hasV116VehicleLocalPosition(r)) {
    position_reader_v1_16_ = p.reader<px4_v1_16::px4_msgs::msg::VehicleLocalPositionPubSubType>(
        position_topic, "px4_out_reader",
        [this](px4_v1_16::px4_msgs::msg::VehicleLocalPosition&& m) { onLocalPosition(wire::localPositionOf(m)); });
  } else {
    position_reader_ = p.reader<px4_msgs::msg::VehicleLocalPositionPubSubType>(
        position_topic, "px4_out_reader",
        [this](px4_msgs::msg::VehicleLocalPosition&& m) { onLocalPosition(wire::localPositionOf(m)); });
  }
}

BridgeNode::~BridgeNode() { participant_.reset(); }

double BridgeNode::nowS() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
}

void BridgeNode::onAttitude(px4_msgs::msg::VehicleAttitude&& m) {
  const auto received = std::chrono::steady_clock::now();
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!px4_reads_) {
    pending_ = std::move(m);
    pending_at_ = received;
    return;
  }
  forward(m, received);
}

void BridgeNode::forward(const px4_msgs::msg::VehicleAttitude& m, std::chrono::steady_clock::time_point received) {
  const double now = nowS();
  if (const std::optional<agent::ImuSample> imu = core_.onAttitude(m.timestamp(), wire::quaternionOf(m), now)) {
    if (imu_seq_ == 0) {
      std::fprintf(stderr, "swa_px4_bridge %d: first attitude from PX4 (timestamp %llu us), forwarding to %s\n", id_,
                   static_cast<unsigned long long>(m.timestamp()), topics::imu(id_).c_str());
    }
    msg::Imu out = wire::toMsg(*imu, static_cast<std::uint32_t>(id_), ++imu_seq_);
    imu_.write(out);
    timings_.push_back({m.timestamp(), received, std::chrono::steady_clock::now()});
    if (timings_.size() > kTimedSamples) timings_.pop_front();
  }
  send(core_.tick(now));
  report();
}

void BridgeNode::onStatus(std::uint8_t arming_state, std::uint8_t nav_state) {
  const std::lock_guard<std::mutex> lock(mutex_);
  status_seen_ = true;
  core_.onStatus(arming_state, nav_state);
  report();
}

void BridgeNode::onGps(const px4::GpsReport& gps) {
  const std::lock_guard<std::mutex> lock(mutex_);
  gnss_forward_.onGps(gps);
}

void BridgeNode::onLocalPosition(const px4::LocalPositionReport& position) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const std::optional<agent::GnssSample> g = gnss_forward_.onLocalPosition(position);
  if (!g) return;
  if (!gnss_reported_ || g->valid != last_gnss_valid_) {
    std::fprintf(stderr, "swa_px4_bridge %d: GNSS from PX4 %s (forwarded to %s)\n", id_,
                 g->valid ? "valid: a 3D fix and a valid horizontal position" : "LOST: no 3D fix or no valid position",
                 topics::gnss(id_).c_str());
    gnss_reported_ = true;
    last_gnss_valid_ = g->valid;
  }
  msg::GnssFix m = wire::toMsg(*g, static_cast<std::uint32_t>(id_), ++gnss_seq_);
  gnss_.write(m);
}

void BridgeNode::onAck(px4_msgs::msg::VehicleCommandAck&& m) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const char* what = m.command() == px4::kCmdComponentArmDisarm ? "arm" : m.command() == px4::kCmdDoSetMode ? "offboard"
                                                                                                              : "?";
  std::fprintf(stderr, "swa_px4_bridge %d: PX4 answered the %s request: result %u (0 accepted)\n", id_, what,
               static_cast<unsigned>(m.result()));
}

void BridgeNode::onCommand(msg::VelocitySetpoint&& m, const dds::WriterGuid& writer) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (const dds::PeerKey& gone : participant_->takePeersGone()) gate_.participantGone(gone);
  if (gate_.admit(0, writer, std::chrono::steady_clock::now()) == dds::Admission::kRefused) {
    if (gate_.firstRefusal(0, writer)) {
      std::fprintf(stderr, "swa_px4_bridge %d: a second writer on %s while the current one is active: refused\n", id_,
                   topics::cmdVel(id_).c_str());
    }
    return;
  }
  if (m.uav_id() != static_cast<std::uint32_t>(id_)) {
    if (commands_foreign_++ == 0) {
      std::fprintf(stderr, "swa_px4_bridge %d: dropping a command addressed to UAV %u\n", id_, m.uav_id());
    }
    return;
  }
  const auto command_in = std::chrono::steady_clock::now();
  const px4::Outbox out = core_.onCommand(wire::fromMsg(m), nowS());
  send(out);
  if (out.setpoint) {
    const auto sent = std::chrono::steady_clock::now();
    const auto t = std::find_if(timings_.begin(), timings_.end(),
                                [&](const Timing& x) { return x.timestamp_us == out.setpoint->timestamp_us; });
    if (t != timings_.end()) {
      const auto ns = [](auto d) { return std::chrono::duration_cast<std::chrono::nanoseconds>(d).count(); };
      hop_.add(ns(sent - t->in));
      agent_loop_.add(ns(command_in - t->imu_out));
      bridge_part_.add(ns(sent - t->in) - ns(command_in - t->imu_out));
    }
  }
  report();
}

void BridgeNode::send(const px4::Outbox& out) {
  if (out.setpoint) {
    px4_msgs::msg::TrajectorySetpoint m = wire::trajectorySetpoint(*out.setpoint);
    setpoint_.write(m);
  }
  if (out.heartbeat_us) {
    px4_msgs::msg::OffboardControlMode m = wire::velocityControlMode(*out.heartbeat_us);
    offboard_.write(m);
  }
  if (out.request && vehicle_command_) {
    px4_msgs::msg::VehicleCommand m =
        wire::vehicleCommand(*out.request, static_cast<std::uint8_t>(options_.target_system));
    vehicle_command_.write(m);
  }
}

void BridgeNode::report() {
  bool changed = false;
  for (std::string& e : core_.takeEvents()) {
    std::fprintf(stderr, "swa_px4_bridge %d: %s\n", id_, e.c_str());
    last_event_ = std::move(e);
    changed = true;
  }
  const auto now = std::chrono::steady_clock::now();
  if (!changed && now - last_state_ < kStatePeriod) return;
  last_state_ = now;
  msg::BridgeState m = wire::bridgeState(core_, static_cast<std::uint32_t>(id_), ++state_seq_,
                                         gate_.refused() + commands_foreign_, last_event_);
  state_.write(m);
}

int BridgeNode::run() {
  std::fprintf(stderr, "swa_px4_bridge %d: PX4 %s namespace '%s' (%s, %s), agent topics %s*\n", id_,
               px4::releaseName(options_.px4_release), ns_.c_str(), topics::px4Out(ns_, "vehicle_attitude").c_str(),
               status_topic_.c_str(), topics::uavPrefix(id_).c_str());
  bool waiting_reported = false, status_missing_reported = false;
  while (!stop_requested_) {
    std::this_thread::sleep_for(kTickPeriod);
    // Matched-status queries outside mutex_ (a listener may hold its reader's lock while it waits for mutex_).
    const bool reads = setpoint_.matched() > 0 && offboard_.matched() > 0;
    const bool agent_matched = imu_.matched() > 0 && cmd_reader_.matched() > 0;
    if (participant_->mustGiveWay()) {
      const std::optional<dds::Peer> twin = participant_->twin();
      std::fprintf(stderr,
                   "swa_px4_bridge %d: REFUSING to run: another swa_px4_bridge %d (pid %ld on host %s) already runs "
                   "in this swarm; two bridges would both command the vehicle\n",
                   id_, id_, twin ? twin->card->pid : 0L, twin ? twin->card->host.c_str() : "?");
      participant_.reset();
      return kExitTwin;
    }
    // A stalled DDS Security handshake with PX4 (or the simulator) or with the agent, before anything flowed
    // (handshake_watch.h): a new participant.
    if (handshake_.stalled(core_.counters().attitude_in > 0, reads && agent_matched && attitude_reader_.matched() > 0,
                           std::chrono::steady_clock::now())) {
      std::fprintf(stderr,
                   "swa_px4_bridge %d: PX4's or the agent's endpoints not matched with DDS Security on (a stalled "
                   "authentication handshake, see deploy/README.md): re-creating the participant (reconnection %d)\n",
                   id_, handshake_.reconnects());
      participant_.reset();  // waits for the listeners, which take mutex_: not held here
      connect();
      const std::lock_guard<std::mutex> lock(mutex_);
      px4_reads_ = false;  // the new writers must match PX4 again before anything is forwarded
      continue;
    }
    const std::lock_guard<std::mutex> lock(mutex_);
    if (reads && !px4_reads_) {
      px4_reads_ = true;
      std::fprintf(stderr, "swa_px4_bridge %d: PX4 reads %s: streaming\n", id_,
                   topics::px4In(ns_, "trajectory_setpoint").c_str());
      if (pending_) forward(*std::exchange(pending_, std::nullopt), pending_at_);
    } else if (!px4_reads_ && !waiting_reported &&
               std::chrono::steady_clock::now() - started_ > std::chrono::seconds(5)) {
      waiting_reported = true;
      std::fprintf(stderr, "swa_px4_bridge %d: no reader of %s after 5 s: is PX4's uXRCE-DDS agent on this domain, "
                           "with namespace '%s'?\n",
                   id_, topics::px4In(ns_, "trajectory_setpoint").c_str(), ns_.c_str());
    }
    // PX4 sends vehicle_status at least every second; attitude but no status is the mark of another release.
    if (!status_seen_ && !status_missing_reported && core_.counters().attitude_in > 0 &&
        std::chrono::steady_clock::now() - started_ > std::chrono::seconds(5)) {
      status_missing_reported = true;
      std::fprintf(stderr,
                   "swa_px4_bridge %d: attitude from PX4 but no %s after 5 s: is the vehicle PX4 %s? (--px4-release; "
                   "v1.15 names it vehicle_status, v1.16 and later vehicle_status_v1 with another layout)\n",
                   id_, topics::px4Out(ns_, status_topic_).c_str(), px4::releaseName(options_.px4_release));
    }
    send(core_.tick(nowS()));
    report();
  }
  participant_.reset();
  logFinalCounts();
  writeSummary();
  return 0;
}

void BridgeNode::logFinalCounts() const {
  const px4::BridgeCounters& c = core_.counters();
  std::fprintf(stderr,
               "swa_px4_bridge %d: stopping on signal %d after %llu attitude samples (%llu rejected, %llu out of "
               "order), %llu commands (%llu applied, %llu replayed, %llu not newer, %llu for unknown samples, %llu "
               "non-finite, %llu clamped, %llu from another writer); sent %llu setpoints, %llu heartbeats, %llu "
               "requests\n",
               id_, app::shutdownSignal(), static_cast<unsigned long long>(c.attitude_in),
               static_cast<unsigned long long>(c.attitude_rejected),
               static_cast<unsigned long long>(c.attitude_out_of_order), static_cast<unsigned long long>(c.commands_in),
               static_cast<unsigned long long>(c.commands_applied),
               static_cast<unsigned long long>(c.commands_replayed),
               static_cast<unsigned long long>(c.commands_not_newer),
               static_cast<unsigned long long>(c.commands_unknown_sample),
               static_cast<unsigned long long>(c.commands_nonfinite),
               static_cast<unsigned long long>(c.commands_clamped), static_cast<unsigned long long>(gate_.refused()),
               static_cast<unsigned long long>(c.setpoints_out), static_cast<unsigned long long>(c.heartbeats_out),
               static_cast<unsigned long long>(c.requests_out));
  const auto us = [](const app::LogHistogram& h, double q) { return h.quantileNs(q) * 1e-3; };
  std::fprintf(stderr,
               "swa_px4_bridge %d: latency over %llu answered samples, p50 / p99: attitude in -> setpoint out %.0f / "
               "%.0f us; of which the agent (imu out -> cmd_vel in) %.0f / %.0f us, the bridge %.0f / %.0f us\n",
               id_, static_cast<unsigned long long>(hop_.count()), us(hop_, 0.5), us(hop_, 0.99), us(agent_loop_, 0.5),
               us(agent_loop_, 0.99), us(bridge_part_, 0.5), us(bridge_part_, 0.99));
}

void BridgeNode::writeSummary() const {
  if (options_.summary_out.empty()) return;
  const px4::BridgeCounters& c = core_.counters();
  const auto us = [](const app::LogHistogram& h, double q) {
    const double v = h.quantileNs(q) * 1e-3;
    return std::isfinite(v) ? std::to_string(v) : std::string("null");
  };
  std::ofstream out(options_.summary_out);
  out << "{\n  \"uav\": " << id_ << ",\n  \"attitude_in\": " << c.attitude_in
      << ",\n  \"commands_applied\": " << c.commands_applied << ",\n  \"setpoints_out\": " << c.setpoints_out
      << ",\n  \"heartbeats_out\": " << c.heartbeats_out << ",\n  \"answered_samples\": " << hop_.count()
      << ",\n  \"hop_p50_us\": " << us(hop_, 0.5) << ",\n  \"hop_p99_us\": " << us(hop_, 0.99)
      << ",\n  \"agent_loop_p50_us\": " << us(agent_loop_, 0.5) << ",\n  \"agent_loop_p99_us\": "
      << us(agent_loop_, 0.99) << ",\n  \"bridge_part_p50_us\": " << us(bridge_part_, 0.5)
      << ",\n  \"bridge_part_p99_us\": " << us(bridge_part_, 0.99) << "\n}\n";
  if (!out.flush()) {
    std::fprintf(stderr, "swa_px4_bridge %d: cannot write --summary-out %s\n", id_, options_.summary_out.c_str());
  }
}

}  // namespace swa::px4_bridge
