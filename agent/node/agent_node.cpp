#include "agent_node.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include <swa/msg/AgentStatePubSubTypes.h>
#include <swa/msg/DetectionsPubSubTypes.h>
#include <swa/msg/GnssFixPubSubTypes.h>
#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>
#include <swa/ros/Detection3DArrayPubSubTypes.h>
#include <swa/ros/PoseWithCovarianceArrayStampedPubSubTypes.h>
#include <swa/ros/TwistStampedPubSubTypes.h>

#include "swa/app/cpu_time.h"
#include "swa/app/signals.h"
#include "swa/dds/topics.h"
#include "swa/wire/agent_state.h"
#include "swa/wire/mission.h"
#include "swa/wire/ros_detections.h"

namespace swa::agent_node {
namespace {

// Inputs silent this long: the simulator has delivered every sample of the pending step (it publishes a step's
// samples together) and is waiting or has ended, so the pending state is published.
constexpr auto kQuietPeriod = std::chrono::milliseconds(100);
// run()'s checks (matching, silence, twins, the 1 s state heartbeat) need no finer grain than this. A pending state
// is published at its quiet deadline instead, so the loop wakes 10 times a second, not 50 (issue #29: every wake-up
// of an agent costs CPU, and a host runs 100 of them). Below kPollGapLimit with room for a busy host.
constexpr auto kPoll = std::chrono::milliseconds(100);
// The state is published at least this often once the agent has run, and says STAGE_NO_INPUT after this long
// without a valid IMU sample.
constexpr auto kHeartbeat = std::chrono::seconds(1);
// A detection / GNSS sample waits for the IMU of its step at most this much newer sim time (sample_order.h).
constexpr agent::StampNs kHoldLimitNs = 1'000'000'000;
// An IMU sample this recent counts as the samples arriving (100 Hz when the loop runs).
constexpr auto kArrivingWindow = std::chrono::milliseconds(250);
// Reader history depths of swa_sensor_reader and swa_detections_gnss_reader (idl/runtime/dds/profiles.xml): the most
// a re-created participant's readers can be sent again (redelivery_filter.h).
constexpr std::size_t kImuHistory = 1000;
constexpr std::size_t kDetectionsGnssHistory = 100;
// The ground's writer keeps the say until its participant leaves: no silence hands it over (CommandGate).
constexpr auto kNoSilenceHandover = std::chrono::hours(24 * 365 * 100);
// Unflyable missions named in the log one by one; beyond, counted (logged at exit).
constexpr std::uint64_t kMissionRefusalsLogged = 10;

// The Participant validates the whole deployment environment (and reports a bad one as DdsError); here only
// whether security is on matters.
bool isSecure() {
  const char* dir = std::getenv("SWA_SECURITY_DIR");
  return dir != nullptr && *dir != '\0';
}

// The detection adapter of UAV `id`: the body frame the simulator names (uav<I>/fcu) or base_link, and the detector's
// own frame where the configuration places it.
agent::DetectionAdapterConfig adapterConfig(int id, const agent::AgentConfig& config) {
  agent::DetectionAdapterConfig c;
  c.frame_ids = {wire::bodyFrameId(static_cast<std::uint32_t>(id)), "base_link"};
  const agent::SensorConfig& s = config.sensor;
  c.sensor_frame_id = s.detector_frame;
  c.sensor_yaw_rad = s.detector_yaw_deg * M_PI / 180.0;
  c.sensor_offset_m = agent::Vec2(s.detector_x_m, s.detector_y_m);
  c.classes = agent::splitClasses(s.detector_classes);
  c.max_detections = config.limits.max_detections;
  return c;
}

}  // namespace

AgentNode::AgentNode(int uav_id, const agent::AgentConfig& config, int domain_id, const std::string& profiles_file)
    : id_(uav_id),
      domain_id_(domain_id),
      profiles_file_(profiles_file),
      agent_(config),
      feed_(agent_, static_cast<std::uint32_t>(uav_id)),
      adapter_(adapterConfig(uav_id, config)),
      order_(kHoldLimitNs),
      started_(std::chrono::steady_clock::now()),
      last_input_(started_),
      last_state_(started_),
      last_fresh_imu_(started_),
      handshake_(isSecure()),
      mission_gate_(1, kNoSilenceHandover) {
  connect();
}

void AgentNode::onMission(msg::SwarmMission&& m, const dds::WriterGuid& writer) {
  const std::lock_guard<std::mutex> lock(mutex_);
  ++stats_.missions;
  // Departed writers are learnt in run() (every poll): a listener must not touch participant_, which is null while
  // a reconnection deletes the old one.
  const auto now = std::chrono::steady_clock::now();
  if (mission_writer_ == writer && m.header().seq() <= mission_seq_) {
    ++stats_.missions_replayed;  // a re-created reader was sent the command in force again
    return;
  }
  if (mission_gate_.admit(0, writer, now) == dds::Admission::kRefused) {
    ++stats_.missions_other_writer;
    if (mission_gate_.firstRefusal(0, writer)) {
      std::fprintf(stderr,
                   "swa_agent %d: REFUSED a mission on %s from a second writer while the ground station's is there "
                   "(one writer: the first, until its participant leaves); further ones counted\n",
                   id_, dds::topics::kMission);
    }
    return;
  }
  mission_writer_ = writer;
  mission_seq_ = m.header().seq();
  const std::variant<agent::MissionCommand, std::string> read = wire::missionCommandOf(m);
  if (const auto* why = std::get_if<std::string>(&read)) {
    ++stats_.missions_unreadable;
    std::fprintf(stderr, "swa_agent %d: dropped mission %u from the ground: %s\n", id_, m.header().seq(), why->c_str());
    return;
  }
  const agent::MissionCommand& command = std::get<agent::MissionCommand>(read);
  // The agent flies it from its next IMU sample (reportMission), or counts it as one it cannot fly.
  if (agent_.commandMission(command)) {
    mission_arrived_after_ns_ = last_imu_stamp_;
    return;
  }
  if (agent_.diagnostics().mission_commands_refused <= kMissionRefusalsLogged) {
    const agent::AgentConfig& c = agent_.config();
    std::fprintf(
        stderr, "swa_agent %d: dropped mission %u from the ground, it cannot be flown: %s%s\n", id_, m.header().seq(),
        agent::missionCommandProblem(command, c.mission.max_speed_mps, c.limits.max_abs_position_m)
            .value_or("?")
            .c_str(),
        agent_.diagnostics().mission_commands_refused == kMissionRefusalsLogged ? " (further ones counted)" : "");
  }
}

void AgentNode::reportMission() {
  const agent::Diagnostics& d = agent_.diagnostics();
  if (d.mission_commands == missions_flown_) return;
  missions_flown_ = d.mission_commands;
  std::fprintf(stderr,
               "swa_agent %d: mission %u from the ground flown from IMU stamp %lld ns (it arrived after the sample "
               "of %lld ns); plan velocity now (%.3f, %.3f) m/s\n",
               id_, mission_seq_, static_cast<long long>(d.mission_command_stamp_ns),
               static_cast<long long>(mission_arrived_after_ns_), d.plan_velocity_mps.x(), d.plan_velocity_mps.y());
}

AgentNode::~AgentNode() { participant_.reset(); }

void AgentNode::stop() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_requested_ = true;
  }
  wake_.notify_all();
}

int AgentNode::run() {
  while (!stop_requested_) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      auto until = std::chrono::steady_clock::now() + kPoll;
      if (pending_state_ns_) until = std::min(until, last_input_ + kQuietPeriod);
      wake_.wait_until(lock, until, [this] { return stop_requested_.load(); });
    }
    if (stop_requested_) break;
    // Matched-status queries stay outside mutex_: a listener delivering a sample may hold its reader's lock while it
    // waits for mutex_ (seen: every agent of a loaded host stuck after its first samples).
    const Matched matched = matchedNow();
    const std::optional<std::string> lost = endpointsLostAfterPeerReturn(matched);
    // Outside mutex_ as well: a listener delivering a sample would wait while three /proc files are read.
    const std::optional<int> deaf = deaf_ports_.poll(std::chrono::steady_clock::now());
    std::unique_lock<std::mutex> lock(mutex_);
    const auto now = std::chrono::steady_clock::now();
    // The writer of its IMU samples stays matched (alive to discovery), the agent had samples and keeps running, and
    // none comes: a channel from the writer broke (silence_watch.h).
    // Nothing is owed either while a lockstep simulator waits for another agent (world_pause.h).
    const bool running =
        own_stall_.check(now) == app::StallWatch::Clock::duration::zero() && !world_pause_.waiting(now);
    const bool arriving = last_imu_at_ && now - *last_imu_at_ < kArrivingWindow;
    const std::optional<SilenceWatch::Clock::duration> silent =
        imu_silence_.poll(now, arriving, running && last_imu_at_.has_value(), matched[1]);
    // SWA's own detections come at their sensor rate, an empty set included (deploy/README.md, the bridge contract),
    // so their silence while the IMU flows and their writer stays matched is a broken channel too: seen in a secure
    // launch through ArduPilot, where an agent got IMU samples from its bridge but no detection or GNSS fix from the
    // simulator after its first, and its UAV left SWA's control (bench_secure_launch.sh). Foreign detection sources
    // may publish only what they see: not watched.
    const bool detections_arriving = last_detections_at_ && now - *last_detections_at_ < kArrivingWindow;
    const std::optional<SilenceWatch::Clock::duration> detections_silent =
        detections_silence_.poll(now, detections_arriving,
                                 running && arriving && last_detections_at_.has_value() &&
                                     agent_.config().sensor.input == agent::DetectionInput::kSwa,
                                 matched[2]);
    if (pending_state_ns_ && std::chrono::steady_clock::now() - last_input_ >= kQuietPeriod) {
      publishState(*pending_state_ns_);
      pending_state_ns_.reset();
    }
    heartbeat();
    if (participant_->mustGiveWay()) {
      lock.unlock();
      refuseAsTwin();
      return kExitTwin;
    }
    noteYoungerTwins();
    reportWaiting(matched);
    // Drained here too, so that the book of departed peers stays short between missions.
    for (const dds::PeerKey& gone : participant_->takePeersGone()) mission_gate_.participantGone(gone);
    std::string why;
    // What it needs before it can start: a reader of its commands and a writer of its detections (the simulator, or
    // the detection source on a drone); through PX4 these are two peers, and either handshake can stall. Started:
    // its IMU flows and this participant has matched a detection source. An IMU alone is no start: through an
    // autopilot it comes from the bridge, and the handshake with the detection source can stall on its own (a
    // secure launch through PX4 at N = 8: a re-created agent authenticated every peer but the simulator, flew on the
    // bridge's IMU without a detection, and its UAV left SWA's control; bench_secure_launch.sh).
    const bool started = stats_.imu > 0 && matched_once_[2];
    if (deaf) {
      why = dds::deafPortReason(*deaf, "the simulator, a bridge or a detection source");
    } else if (handshake_.stalled(started, matched[0] > 0 && matched[2] > 0, std::chrono::steady_clock::now(),
                                  participant_->lastAuthentication())) {
      why = "no reader of " + dds::topics::cmdVel(id_) + " or no writer of " + detectionsTopic() +
            " with DDS Security on (a stalled authentication handshake, see deploy/README.md)";
    } else if (lost) {
      why = *lost;
    } else if (silent) {
      why = "no sample on " + dds::topics::imu(id_) + " for " +
            std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(*silent).count()) + " ms while " +
            std::to_string(matched[1]) + " writer(s) of it stay matched (a channel from a writer broke)";
    } else if (detections_silent) {
      why = "no sample on " + detectionsTopic() + " for " +
            std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(*detections_silent).count()) +
            " ms while IMU samples arrive and " + std::to_string(matched[2]) +
            " writer(s) of it stay matched (a channel from a writer broke)";
    }
    if (!why.empty()) {
      ++reconnects_;
      std::fprintf(stderr, "swa_agent %d: %s: re-creating the participant (reconnection %d)\n", id_, why.c_str(),
                   reconnects_);
      if (deaf) participant_->abandonAcknowledgments();  // none can reach a deaf port
      lock.unlock();  // deleting the participant waits for its listeners, which take the lock
      participant_.reset();
      lock.lock();
      // Deleting may wait kShutdownAckWaitS for acknowledgments; a stop asked meanwhile (the end of a run, whose
      // simulator has left) gets no new participant, whose deletion would wait as long again and outlast the
      // launcher's 10 s grace (seen once: an agent SIGKILLed after a reconnection at the end of a container run).
      if (stop_requested_) break;
      // The new readers are sent the writers' history again: not news (redelivery_filter.h).
      replay_.arm(Stream::kImu, kImuHistory);
      replay_.arm(Stream::kDetections, kDetectionsGnssHistory);
      replay_.arm(Stream::kGnss, kDetectionsGnssHistory);
      connect();
      // The answer to the newest IMU sample may never have arrived (the old writer was not matched), and that sample
      // comes back only as replayed history: the new writer sends it again (TRANSIENT_LOCAL: once matched). A
      // simulator that already has it ignores the duplicate.
      if (last_cmd_ && cmd_writer_.write(*last_cmd_)) ++stats_.commands;
    }
  }
  participant_.reset();
  logFinalCounts();
  std::fprintf(stderr, "%s\n", app::cpuTimeLine("swa_agent " + std::to_string(id_)).c_str());
  return 0;
}

void AgentNode::logFinalCounts() const {
  const AgentNodeStats& s = stats_;
  std::fprintf(stderr,
               "swa_agent %d: stopping on signal %d after %llu IMU, %llu detection, %llu GNSS samples; %llu commands, "
               "%llu states, %llu foreign samples, %llu write failures\n",
               id_, app::shutdownSignal(), static_cast<unsigned long long>(s.imu),
               static_cast<unsigned long long>(s.detections), static_cast<unsigned long long>(s.gnss),
               static_cast<unsigned long long>(s.commands), static_cast<unsigned long long>(s.states),
               static_cast<unsigned long long>(s.foreign), static_cast<unsigned long long>(s.write_failures));
  // Where the agent stood at the end: a supervisor (or a person reading the log) sees whether it was flying
  // relative to its neighbours when it stopped.
  const agent::Diagnostics& d = agent_.diagnostics();
  const char* stage = d.stage == agent::Stage::kTracking ? "tracking"
                      : d.stage == agent::Stage::kLost   ? "lost"
                                                         : "initializing";
  std::fprintf(stderr, "swa_agent %d: final stage %s, %d confirmed track(s), frame fitted on %d neighbour(s)\n", id_,
               stage, d.confirmed_tracks, d.neighbour_count);
  const agent::RejectCounters& r = d.rejected;
  std::fprintf(stderr,
               "swa_agent %d: inputs rejected: %llu non-finite, %llu out of order, %llu future stamp, %llu oversize, "
               "%llu bad id, %llu implausible, %llu before a heading; %llu stamp resync(s), %llu forced release(s) "
               "from the stamp orderer, %llu replayed sample(s) dropped after a reconnection\n",
               id_, static_cast<unsigned long long>(r.nonfinite), static_cast<unsigned long long>(r.out_of_order),
               static_cast<unsigned long long>(r.future), static_cast<unsigned long long>(r.oversize),
               static_cast<unsigned long long>(r.bad_id), static_cast<unsigned long long>(r.implausible),
               static_cast<unsigned long long>(r.no_heading), static_cast<unsigned long long>(d.stamp_resyncs),
               static_cast<unsigned long long>(order_.forcedReleases()), static_cast<unsigned long long>(s.replayed));
  if (s.missions > 0 || d.mission_commands_refused > 0) {
    std::fprintf(stderr,
                 "swa_agent %d: missions from the ground: %llu received, %llu flown, %llu that could not be flown, "
                 "%llu unreadable, %llu from a second writer refused, %llu sent again after a reconnection dropped\n",
                 id_, static_cast<unsigned long long>(s.missions), static_cast<unsigned long long>(d.mission_commands),
                 static_cast<unsigned long long>(d.mission_commands_refused),
                 static_cast<unsigned long long>(s.missions_unreadable),
                 static_cast<unsigned long long>(s.missions_other_writer),
                 static_cast<unsigned long long>(s.missions_replayed));
  }
  if (d.tilt_fallbacks > 0) {
    std::fprintf(stderr,
                 "swa_agent %d: %llu IMU sample(s) came without the accelerometer focal.imu_source asks for and were "
                 "read from the tilt\n",
                 id_, static_cast<unsigned long long>(d.tilt_fallbacks));
  }
  if (agent_.config().sensor.input == agent::DetectionInput::kSwa) return;
  const agent::DetectionAdapterCounters& a = adapter_.counters();
  const auto u = [](std::uint64_t v) { return static_cast<unsigned long long>(v); };
  std::fprintf(stderr,
               "swa_agent %d: %s detections: %llu set(s) in, %llu passed on; dropped %llu in a frame it cannot place, "
               "%llu with a bad stamp, %llu oversize, %llu detection(s) with a non-finite position, %llu of another "
               "class; covariance repaired %llu, unknown %llu (the configured noise used); %llu anonymous\n",
               id_, agent::toString(agent_.config().sensor.input).c_str(), u(a.sets_in), u(a.sets_out),
               u(a.unknown_frame), u(a.bad_stamp), u(a.oversize), u(a.nonfinite_position), u(a.other_class),
               u(a.covariance_repaired), u(a.covariance_missing), u(a.anonymous));
}

void AgentNode::heartbeat() {
  // Before the first valid IMU sample the agent has nothing to say that its absence does not say (and in lockstep
  // a state stamped before the run would take the place of step 0's).
  if (!had_fresh_imu_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_state_ < kHeartbeat) return;
  // The stamp of the newest processed sample: the monitor's joiner drops it as a duplicate of that step's state.
  publishState(agent_.diagnostics().stamp_ns, now - last_fresh_imu_ >= kHeartbeat);
}

void AgentNode::publishState(agent::StampNs stamp_ns, bool no_input) {
  msg::AgentState state = wire::toMsg(agent_.diagnostics(), static_cast<std::uint32_t>(id_), ++state_seq_);
  state.header().stamp_ns(stamp_ns);  // the step whose samples have all been processed (also if one was rejected)
  if (no_input) state.stage(msg::STAGE_NO_INPUT);
  last_state_ = std::chrono::steady_clock::now();
  if (state_writer_.write(state)) {
    ++stats_.states;
  } else {
    ++stats_.write_failures;
  }
}

}  // namespace swa::agent_node
