#include "bridge_node.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include <swa/msg/AgentStatePubSubTypes.h>
#include <swa/msg/BridgeStatePubSubTypes.h>
#include <swa/msg/GnssFixPubSubTypes.h>
#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>

#include "swa/autopilot/ardupilot.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"
#include "swa/wire/agent_state.h"
#include "swa/wire/px4.h"
#include "swa/wire/samples.h"

namespace swa::bridge_node {
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

// A tilt no multicopter flies at: the attitude is read wrongly (ArduPilot's --ap-quaternion).
constexpr double kImplausibleTiltRad = 1.2;

std::unique_ptr<VehicleLink> makeLink(const BridgeOptions& o, VehicleEvents events) {
  return o.autopilot == AutopilotKind::kArdupilot ? makeArdupilotLink(o, std::move(events))
                                                  : makePx4Link(o, std::move(events));
}

}  // namespace

BridgeNode::BridgeNode(const BridgeOptions& options, int domain_id, const std::string& profiles_file)
    : id_(options.id),
      options_(options),
      domain_id_(domain_id),
      profiles_file_(profiles_file),
      started_(std::chrono::steady_clock::now()),
      vehicle_(makeLink(options, VehicleEvents{[this](std::uint64_t t, const px4::Quaternion& q,
                                                      const std::optional<ardupilot::SpecificForce>& f) {
                                                 onAttitude({t, q, f});
                                               },
                                               [this](bool armed, std::uint8_t mode) { onStatus(armed, mode); },
                                               [this](const agent::GnssSample& g) { onGnss(g); },
                                               [this](const std::string& line) { onVehicleLog(line); },
                                               [this](bool unaided) { onEstimator(unaided); }})),
      core_(options.core),
      gate_(1, kCommandHandover),
      odometry_(options.odometry),
      handshake_(isSecure()),
      requests_handshake_(isSecure() && options.core.engage) {
  connect();
}

void BridgeNode::connect() {
  auto participant =
      std::make_unique<dds::Participant>("swa_bridge_" + std::to_string(id_), domain_id_, profiles_file_);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    participant_ = std::move(participant);
  }
  connected_at_ = std::chrono::steady_clock::now();
  waiting_reported_ = false;
  handshake_.connected(std::chrono::steady_clock::now());
  requests_handshake_.connected(std::chrono::steady_clock::now());
  dds::sayOwnSharedMemoryPorts("swa_px4_bridge " + std::to_string(id_));
  deaf_ports_.reset();
  dds::Participant& p = *participant_;
  imu_ = p.writer<msg::ImuPubSubType>(topics::imu(id_), dds::qos::kSensorWriter);
  state_ = p.writer<msg::BridgeStatePubSubType>(topics::bridgeState(id_), dds::qos::kStateWriter);
  if (!options_.no_gnss) gnss_ = p.writer<msg::GnssFixPubSubType>(topics::gnss(id_), dds::qos::kDetectionsGnssWriter);
  // The vehicle's endpoints before the command reader: a command arriving at once is sent through the new
  // participant's writers, never through those of a participant deleted by a reconnection.
  vehicle_->connect(p);
  cmd_reader_ = p.readerWithOrigin<msg::VelocitySetpointPubSubType>(
      topics::cmdVel(id_), dds::qos::kCommandReader,
      [this](msg::VelocitySetpoint&& m, const dds::WriterGuid& w) { onCommand(std::move(m), w); });
  if (options_.odometry.mode != autopilot::OdometryMode::kOff) {
    state_reader_ = p.reader<msg::AgentStatePubSubType>(topics::state(id_), dds::qos::kStateReader,
                                                        [this](msg::AgentState&& m) { onAgentState(std::move(m)); });
  }
}

BridgeNode::~BridgeNode() { closeParticipant(); }

void BridgeNode::reconnect() {
  closeParticipant();
  connect();
  const std::lock_guard<std::mutex> lock(mutex_);
  vehicle_reads_ = false;  // the new writers must match the vehicle again before anything is forwarded
  // The new IMU writer's history is empty, and a vehicle repeats the attitude it waits on (a lockstep simulator
  // does) with the same timestamp, which is not forwarded twice: without this the agent would never get the sample
  // its vehicle waits for. Seen in a secure launch through PX4: a UAV declared dead after 60 s. An agent that had it
  // already drops it as re-delivered.
  if (last_imu_) imu_.write(*last_imu_);
}

void BridgeNode::closeParticipant() {
  std::unique_ptr<dds::Participant> closing;
  {
    // Listeners test participant_ under mutex_: from here on they return at once, and none is still inside.
    const std::lock_guard<std::mutex> lock(mutex_);
    closing = std::move(participant_);
  }
  closing.reset();  // waits for the listeners to return, which take mutex_: not held here
}

double BridgeNode::nowS() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
}

void BridgeNode::onAttitude(const Attitude& a) {
  const auto received = std::chrono::steady_clock::now();
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!participant_) return;  // closing (closeParticipant)
  if (!newest_attitude_ || a.timestamp_us >= newest_attitude_->timestamp_us) newest_attitude_ = a;
  if (!vehicle_reads_) {
    pending_ = a;
    pending_at_ = received;
    return;
  }
  forward(a, received);
}

void BridgeNode::forward(const Attitude& a, std::chrono::steady_clock::time_point received) {
  const double now = nowS();
  if (const std::optional<agent::ImuSample> imu = core_.onAttitude(a.timestamp_us, a.q, now, a.force_frd)) {
    if (imu_seq_ == 0) {
      std::fprintf(stderr, "swa_px4_bridge %d: first attitude from %s (timestamp %llu us), forwarding to %s\n", id_,
                   core_.autopilot().name, static_cast<unsigned long long>(a.timestamp_us), topics::imu(id_).c_str());
    }
    // With an order given by hand (auto decides it from gravity, which a wrong order contradicts).
    if (!upside_down_reported_ && options_.autopilot == AutopilotKind::kArdupilot && options_.ap_quaternion &&
        (std::abs(imu->roll_rad) > kImplausibleTiltRad || std::abs(imu->pitch_rad) > kImplausibleTiltRad)) {
      upside_down_reported_ = true;
      std::fprintf(stderr,
                   "swa_px4_bridge %d: WARNING: ArduPilot's attitude reads as roll %.0f deg, pitch %.0f deg: is the "
                   "IMU message's quaternion in another field order? (--ap-quaternion, now %s)\n",
                   id_, imu->roll_rad * 180.0 / M_PI, imu->pitch_rad * 180.0 / M_PI,
                   ardupilot::quaternionLayoutName(*options_.ap_quaternion));
    }
    msg::Imu out = wire::toMsg(*imu, static_cast<std::uint32_t>(id_), ++imu_seq_);
    imu_.write(out);
    last_imu_ = std::move(out);
    timings_.push_back({a.timestamp_us, received, std::chrono::steady_clock::now()});
    if (timings_.size() > kTimedSamples) timings_.pop_front();
  } else if (last_answer_ && last_answer_->timestamp_us == a.timestamp_us &&
             core_.newestTimestampUs() == std::optional<std::uint64_t>(a.timestamp_us) &&
             core_.link() == autopilot::Link::kFresh) {
    // The vehicle sent the sample it waits on once more (a lockstep simulator does; PX4 and ArduPilot never repeat a
    // stamp). Our answer to it is lost: a best-effort setpoint, or one written just before this participant was
    // re-created (a secure launch through PX4 stalled 60 s so). The agent's own resend of its command is "not newer"
    // here, so the answer goes again from here; only while the link streams (never past the core's own stops).
    autopilot::Outbox again;
    again.setpoint = last_answer_;
    vehicle_->send(again);
    ++answers_repeated_;
  }
  vehicle_->send(core_.tick(now));
  if (const std::optional<agent::StampNs> t = px4::stampNsOf(a.timestamp_us); t && odometry_.expire(*t)) {
    feeding_since_us_.reset();
    std::fprintf(stderr,
                 "swa_px4_bridge %d: odometry to %s stopped: no fresh state from the agent for %.1f s (%llu sent); "
                 "nothing more is fed, the autopilot's own failsafe decides\n",
                 id_, core_.autopilot().name, options_.odometry.stale_after_s,
                 static_cast<unsigned long long>(odometry_.counters().sent));
  }
  report();
}

void BridgeNode::onStatus(bool armed, std::uint8_t mode) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!participant_) return;
  status_seen_ = true;
  core_.onStatus(armed, mode);
  if (armed && mode == core_.autopilot().control_mode) engaged_ = true;
  report();
}

void BridgeNode::onGnss(const agent::GnssSample& g) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!participant_ || !gnss_) return;
  if (!gnss_reported_ || g.valid != last_gnss_valid_) {
    std::fprintf(stderr, "swa_px4_bridge %d: GNSS from %s %s (forwarded to %s)\n", id_, core_.autopilot().name,
                 g.valid ? "valid: a fix and a position" : "LOST: no fix, no valid position, or no report for too long",
                 topics::gnss(id_).c_str());
    gnss_reported_ = true;
    last_gnss_valid_ = g.valid;
  }
  msg::GnssFix m = wire::toMsg(g, static_cast<std::uint32_t>(id_), ++gnss_seq_);
  gnss_.write(m);
}

void BridgeNode::onAgentState(msg::AgentState&& m) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!participant_ || !newest_attitude_ || m.uav_id() != static_cast<std::uint32_t>(id_)) return;
  const agent::Diagnostics d = wire::fromMsg(m).diagnostics;
  const bool was_feeding = odometry_.feeding();
  const std::uint64_t vehicle_us = newest_attitude_->timestamp_us;
  const std::optional<autopilot::Odometry> o = odometry_.onState(d, px4::stampNsOf(vehicle_us).value_or(0));
  if (o) vehicle_->sendOdometry(*o, newest_attitude_->q);
  if (odometry_.feeding() == was_feeding) return;
  if (odometry_.feeding()) {
    feeding_since_us_ = vehicle_us;
    not_fusing_reported_ = false;
    std::fprintf(stderr, "swa_px4_bridge %d: feeding the agent's estimate to %s as external odometry on %s (%s)\n", id_,
                 core_.autopilot().name, vehicle_->odometryTopic().c_str(),
                 d.gnss_valid ? "--odometry always" : "the agent has no GNSS");
  } else {
    feeding_since_us_.reset();
    const autopilot::OdometryCounters& c = odometry_.counters();
    std::fprintf(stderr, "swa_px4_bridge %d: odometry to %s stopped: %s (%llu sent)\n", id_, core_.autopilot().name,
                 d.gnss_valid && options_.odometry.mode != autopilot::OdometryMode::kAlways
                     ? "the agent has GNSS again, the autopilot's own is used"
                     : "the agent's estimate is stale or not valid (not tracking, not finite, too uncertain)",
                 static_cast<unsigned long long>(c.sent));
  }
}

void BridgeNode::onEstimator(bool unaided) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!participant_) return;
  if (!unaided) {
    not_fusing_reported_ = false;
    return;
  }
  // Fed for a second and more (PX4 starts external vision within 0.2 s, ArduPilot's EKF failsafe needs 8 s of no
  // position): the autopilot does not fuse what it gets.
  if (not_fusing_reported_ || !feeding_since_us_ || !newest_attitude_ ||
      newest_attitude_->timestamp_us < *feeding_since_us_ + 1'000'000) {
    return;
  }
  not_fusing_reported_ = true;
  std::fprintf(
      stderr,
      "swa_px4_bridge %d: %s reports no aiding (%s) although this bridge has fed it the agent's estimate on "
      "%s for %.1f s: it is not fusing it; %s\n",
      id_, core_.autopilot().name,
      options_.autopilot == AutopilotKind::kArdupilot ? "EKF failsafe" : "vehicle_local_position.dead_reckoning",
      vehicle_->odometryTopic().c_str(),
      static_cast<double>(newest_attitude_->timestamp_us - *feeding_since_us_) * 1e-6,
      vehicle_->odometryHint().c_str());
}

void BridgeNode::onVehicleLog(const std::string& line) {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::fprintf(stderr, "swa_px4_bridge %d: %s\n", id_, line.c_str());
}

void BridgeNode::onCommand(msg::VelocitySetpoint&& m, const dds::WriterGuid& writer) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!participant_) return;
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
  const autopilot::Outbox out = core_.onCommand(wire::fromMsg(m), nowS());
  vehicle_->send(out);
  if (out.setpoint) {
    last_answer_ = out.setpoint;
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
  std::fprintf(stderr, "swa_px4_bridge %d: %s, agent topics %s*\n", id_, vehicle_->description().c_str(),
               topics::uavPrefix(id_).c_str());
  bool status_missing_reported = false;
  while (!stop_requested_) {
    std::this_thread::sleep_for(kTickPeriod);
    // Matched-status queries outside mutex_ (a listener may hold its reader's lock while it waits for mutex_).
    const bool reads = vehicle_->readsCommands();
    const bool agent_matched = imu_.matched() > 0 && cmd_reader_.matched() > 0;
    bool running = false, agent_lost = false, attitude_seen = false;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      running = core_.link() == autopilot::Link::kFresh || core_.link() == autopilot::Link::kStale;
      agent_lost = core_.link() == autopilot::Link::kAgentLost;
      attitude_seen = core_.counters().attitude_in > 0;
    }
    if (participant_->mustGiveWay()) {
      const std::optional<dds::Peer> twin = participant_->twin();
      std::fprintf(stderr,
                   "swa_px4_bridge %d: REFUSING to run: another swa_px4_bridge %d (pid %ld on host %s) already runs "
                   "in this swarm; two bridges would both command the vehicle\n",
                   id_, id_, twin ? twin->card->pid : 0L, twin ? twin->card->host.c_str() : "?");
      closeParticipant();
      return kExitTwin;
    }
    if (const std::optional<int> deaf = deaf_ports_.poll(std::chrono::steady_clock::now())) {
      std::fprintf(stderr, "swa_px4_bridge %d: %s: re-creating the participant\n", id_,
                   dds::deafPortReason(*deaf, "the vehicle and the agent").c_str());
      participant_->abandonAcknowledgments();  // none can reach a deaf port
      reconnect();
      continue;
    }
    // A stalled DDS Security handshake with the vehicle (or the simulator) or with the agent while the loop does not
    // run (handshake_watch.h): a new participant. "Agent lost" with every endpoint matched counts as stalled too: with
    // security on, a channel can break with both sides still matched (measured: two agents of a secure 4-UAV launch
    // through ArduPilot got no IMU sample after the first, and re-creating their own participants five times did not
    // mend it).
    if (handshake_.stalled(running, reads && agent_matched && vehicle_->attitudeMatched() && !agent_lost,
                           std::chrono::steady_clock::now(), participant_->lastAuthentication())) {
      std::fprintf(
          stderr,
          "swa_px4_bridge %d: the vehicle's or the agent's endpoints not matched, or the agent lost while they "
          "are, with DDS Security on (a stalled handshake or a broken channel, see deploy/README.md): "
          "re-creating the participant (reconnection %d)\n",
          id_, handshake_.reconnects());
      reconnect();
      continue;
    }
    if (requests_handshake_.stalled(engaged_, vehicle_->requestsMatched(), std::chrono::steady_clock::now(),
                                    participant_->lastAuthentication())) {
      std::fprintf(stderr,
                   "swa_px4_bridge %d: --engage's requests to %s (arm, mode) not matched with DDS Security on, and the "
                   "vehicle not engaged yet: re-creating the participant (reconnection %d)\n",
                   id_, core_.autopilot().name, requests_handshake_.reconnects());
      reconnect();
      continue;
    }
    const std::lock_guard<std::mutex> lock(mutex_);
    if (reads && !vehicle_reads_) {
      vehicle_reads_ = true;
      std::fprintf(stderr, "swa_px4_bridge %d: %s reads %s: streaming\n", id_, core_.autopilot().name,
                   vehicle_->commandTopic().c_str());
      if (pending_) forward(*std::exchange(pending_, std::nullopt), pending_at_);
    } else if (!vehicle_reads_ && !waiting_reported_ &&
               std::chrono::steady_clock::now() - connected_at_ > std::chrono::seconds(5)) {
      waiting_reported_ = true;
      std::fprintf(stderr, "swa_px4_bridge %d: no reader of %s after 5 s: %s\n", id_, vehicle_->commandTopic().c_str(),
                   vehicle_->noReaderHint().c_str());
    }
    // PX4 sends vehicle_status at least every second, ArduPilot its status on every change (transient local: a late
    // reader gets the newest); attitude but no status is the mark of another release.
    if (!status_seen_ && !status_missing_reported && attitude_seen &&
        std::chrono::steady_clock::now() - started_ > std::chrono::seconds(5)) {
      status_missing_reported = true;
      std::fprintf(stderr, "swa_px4_bridge %d: attitude from %s but after 5 s %s\n", id_, core_.autopilot().name,
                   vehicle_->noStatusHint().c_str());
    }
    vehicle_->send(core_.tick(nowS()));
    report();
  }
  closeParticipant();
  logFinalCounts();
  writeSummary();
  return 0;
}

}  // namespace swa::bridge_node
