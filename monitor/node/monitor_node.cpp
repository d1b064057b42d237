#include "monitor_node.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>

#include <swa/msg/AgentStatePubSubTypes.h>
#include <swa/msg/ScenarioEventPubSubTypes.h>
#include <swa/msg/SwarmMissionPubSubTypes.h>
#include <swa/msg/SwarmTruthPubSubTypes.h>

#include "msg_convert.h"
#include "recording_taps.h"
#include "swa/app/signals.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"
#include "swa/wire/mission.h"

namespace swa::monitor_node {
namespace {

using recording::recordingChannel;
using recording::tapClock;
using recording::tapUavTopics;

// Longest single wait, so a signal or the timeout is noticed quickly.
constexpr auto kPollPeriod = std::chrono::milliseconds(100);
// The ground's writer keeps the say until its participant leaves, as in the agents (agent_node.cpp).
constexpr auto kNoSilenceHandover = std::chrono::hours(24 * 365 * 100);
// Longest wait for every agent's state writer before the run is read without the missing ones.
constexpr auto kStateMatchWait = std::chrono::seconds(30);
// Recording: how long the recorder's readers must have been matched before the simulator may start. A reader matches
// a writer when it has discovered it, but the writer sends to the reader only once it has discovered the reader in
// turn; until then an agent's commands (a writer that keeps only its newest one) would not reach the recording
// (measured: the first 8 to 24 commands of a UAV missing in about one run in three without this wait).
constexpr auto kRecorderSettle = std::chrono::seconds(1);

std::string signalName(int signal) {
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGTERM) return "SIGTERM";
  return "signal " + std::to_string(signal);
}

}  // namespace

MonitorNode::MonitorNode(LiveRun& run, const MonitorNodeOptions& options, int domain_id,
                         const std::string& profiles_file)
    : run_(run),
      options_(options),
      pacer_(isatty(fileno(stderr)) != 0),
      domain_id_(domain_id),
      profiles_file_(profiles_file),
      handshake_(std::getenv("SWA_SECURITY_DIR") != nullptr && *std::getenv("SWA_SECURITY_DIR") != '\0'),
      mission_gate_(1, kNoSilenceHandover) {
  if (options_.uav_count) {
    for (int i = 0; i < *options_.uav_count; ++i) state_readers_.insert(i);
  } else {
    readers_from_truth_pending_ = true;
  }
  connect();
  std::fprintf(stderr, "swa_monitor: listening on domain %d for %s\n", domain_id,
               options_.uav_count ? (std::to_string(*options_.uav_count) + " UAV(s)").c_str()
                                  : "the UAVs of the first truth sample");
}

MonitorNode::~MonitorNode() { participant_.reset(); }

template <class PubSubType, class Push>
dds::Reader<dds::Payload> MonitorNode::readAndRecord(const std::string& topic, const char* profile, Push push) {
  std::optional<std::uint16_t> channel;
  if (options_.recording != nullptr) {
    channel = recordingChannel<PubSubType>(*options_.recording, *participant_, topic);
  }
  return participant_->rawReader<PubSubType>(topic, profile, [this, channel, push](dds::RawSample&& s) {
    // Once in the recording, also when a re-created reader gets its writer's history again (Recording::firstDelivery).
    if (channel && options_.recording->firstDelivery(*channel, s.id.writer, s.id.seq)) {
      options_.recording->writeCdr(*channel, s.payload, s.source_time_ns);
    }
    typename PubSubType::type m;
    if (dds::decodePayload<PubSubType>(s.payload, m)) {
      push(std::move(m));
    } else {
      ++undecodable_;
    }
  });
}

void MonitorNode::connect() {
  participant_ = std::make_unique<dds::Participant>("swa_monitor", domain_id_, profiles_file_);
  connected_at_ = std::chrono::steady_clock::now();
  dds::sayOwnSharedMemoryPorts("swa_monitor");
  deaf_ports_.reset();
  handshake_.connected(connected_at_);
  state_reader_handles_.clear();
  uav_taps_.clear();
  truth_reader_ = {};
  for (const int uav : state_readers_) createStateReader(uav);
  if (recordsEveryTopic()) tapClock(*participant_, *options_.recording);
  // From the start, so that the time a command arrives is the time the agents got it, not when a reader came late.
  mission_reader_ = participant_->readerWithOrigin<msg::SwarmMissionPubSubType>(
      dds::topics::kMission, dds::qos::kMissionReader, [this](msg::SwarmMission&& m, const dds::WriterGuid& writer) {
        queue_.push(MissionInput{writer, std::move(m)});
      });
  // With a known swarm, the truth and event readers wait until every agent's state writer is matched (see
  // createRunReadersWhenReady); without one, the UAVs are only known from the first truth sample.
  run_readers_pending_ = options_.uav_count.has_value();
  all_matched_at_.reset();
  if (!run_readers_pending_) createRunReaders();
}

void MonitorNode::createRunReaders() {
  readAndRecord<msg::ScenarioEventPubSubType>(dds::topics::kEvents, dds::qos::kEventReader,
                                              [this](msg::ScenarioEvent&& m) { queue_.push(std::move(m)); });
  truth_reader_ = readAndRecord<msg::SwarmTruthPubSubType>(dds::topics::kTruth, dds::qos::kTruthReader,
                                                           [this](msg::SwarmTruth&& m) { queue_.push(std::move(m)); });
}

void MonitorNode::createRunReadersWhenReady() {
  // The simulator starts once it has matched every agent and the monitor's truth reader (--wait-monitors), but
  // discovery is pairwise: the monitor could match an agent's state writer later, and the states of the steps
  // already joined and released meanwhile would be lost (measured in containers: ~45 steps per agent). So the
  // truth reader, the simulator's signal that the monitor is ready, appears only once every state writer (and,
  // recording, every UAV's command writer and sensor writer: recording_taps.h, UavTaps) is matched, or after
  // kStateMatchWait with a warning (an agent that never starts must not block the run).
  if (!run_readers_pending_) return;
  std::vector<int> unmatched;
  for (const auto& [uav, reader] : state_reader_handles_) {
    const auto tap = uav_taps_.find(uav);
    if (reader.matched() < 1 || (tap != uav_taps_.end() && !tap->second.matched())) unmatched.push_back(uav);
  }
  const auto now = std::chrono::steady_clock::now();
  const bool waited_enough = now - connected_at_ >= kStateMatchWait;
  if (!unmatched.empty() && !waited_enough) return;
  if (!uav_taps_.empty() && unmatched.empty()) {
    if (!all_matched_at_) all_matched_at_ = now;
    if (now - *all_matched_at_ < kRecorderSettle) return;
  }
  if (!unmatched.empty()) {
    std::string list;
    for (const int uav : unmatched) list += " " + std::to_string(uav);
    std::fprintf(stderr,
                 "swa_monitor: no state (or, recording, command or sensor) writer of UAV(s)%s after %.0f s; reading "
                 "the run without them\n",
                 list.c_str(), std::chrono::duration<double>(kStateMatchWait).count());
  }
  run_readers_pending_ = false;
  createRunReaders();
}

void MonitorNode::subscribeState(int uav) {
  if (state_readers_.insert(uav).second) createStateReader(uav);
}

void MonitorNode::createStateReader(int uav) {
  state_reader_handles_[uav] = readAndRecord<msg::AgentStatePubSubType>(dds::topics::state(uav), dds::qos::kStateReader,
                                                                        [this, uav](msg::AgentState&& m) {
                                                                          queue_.push(StateInput{uav, std::move(m)});
                                                                        });
  if (recordsEveryTopic()) uav_taps_[uav] = tapUavTopics(*participant_, *options_.recording, uav);
}

void MonitorNode::reconnectIfHandshakeStalled() {
  // The stalled DDS Security handshake of swa_agent (handshake_watch.h), here with the simulator: before the first
  // truth sample, with no truth writer matched.
  if (!handshake_.stalled(truth_seen_, truth_reader_.matched() > 0, std::chrono::steady_clock::now(),
                          participant_->lastAuthentication()))
    return;
  std::fprintf(stderr,
               "swa_monitor: no writer of %s with DDS Security on: re-creating the participant (reconnection %d; a "
               "stalled authentication handshake, see deploy/README.md)\n",
               dds::topics::kTruth, handshake_.reconnects());
  participant_.reset();
  connect();
}

void MonitorNode::reconnectIfDeaf() {
  const std::optional<int> deaf = deaf_ports_.poll(std::chrono::steady_clock::now());
  if (!deaf) return;
  std::fprintf(stderr, "swa_monitor: %s: re-creating the participant\n",
               dds::deafPortReason(*deaf, "the simulator and the agents").c_str());
  participant_->abandonAcknowledgments();  // none can reach a deaf port
  participant_.reset();
  connect();
}

RunEnd MonitorNode::run() {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const auto elapsed = [&t0] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  std::optional<double> end_seen_s;
  std::vector<Input> batch;
  RunEnd end;
  while (true) {
    batch.clear();
    queue_.drain(batch, kPollPeriod);
    run_.tick(elapsed());
    for (Input& input : batch) process(input);
    publishNewMetrics();
    createRunReadersWhenReady();
    reconnectIfHandshakeStalled();
    reconnectIfDeaf();
    const double now_s = elapsed();
    showStatus(now_s, false);

    if (stop_requested_) {
      end = {false, app::shutdownSignal() != 0 ? "interrupted by " + signalName(app::shutdownSignal()) : "stopped"};
      break;
    }
    if (const std::optional<EventRecord>& e = run_.endEvent()) {
      if (!end_seen_s) end_seen_s = now_s;
      // The last truth sample is stamped like the end event; its states may still be on the way.
      const bool caught_up =
          run_.newestTruth() && stampSeconds(*run_.newestTruth()) >= e->t_s - 1e-9 && run_.joinIdle();
      if (caught_up || now_s - *end_seen_s >= options_.end_grace_s) {
        end = endFromEvent(*e);
        break;
      }
    } else if (options_.timeout_s > 0.0 && now_s >= options_.timeout_s) {
      end = {false, "no EVENT_SCENARIO_END within " + monitor::formatNumber(options_.timeout_s) + " s (--timeout-s)"};
      break;
    }
  }
  showStatus(elapsed(), true);
  return end;
}

void MonitorNode::process(Input& input) {
  if (auto* truth = std::get_if<msg::SwarmTruth>(&input)) {
    truth_seen_ = true;
    if (readers_from_truth_pending_) {
      // Without a scenario the swarm's size is only known from the truth. States published before these readers
      // match come from the agents' history (TRANSIENT_LOCAL, the last 100 s).
      readers_from_truth_pending_ = false;
      for (const msg::UavTruth& u : truth->uavs()) {
        if (u.id() <= 100'000) subscribeState(static_cast<int>(u.id()));
      }
    }
    TruthSample sample = fromTruthMsg(*truth);
    if (options_.live != nullptr) options_.live->onTruth(sample);
    run_.onTruth(std::move(sample));
  } else if (auto* state = std::get_if<StateInput>(&input)) {
    StateSample sample = fromStateMsg(state->state, options_.formation);
    if (options_.live != nullptr && sample.uav == state->topic_uav) options_.live->onState(sample);
    run_.onState(state->topic_uav, std::move(sample));
  } else if (auto* event = std::get_if<msg::ScenarioEvent>(&input)) {
    if (auto record = fromEventMsg(*event)) {
      run_.onEvent(std::move(*record));
    } else {
      run_.onUnknownEvent();
    }
  } else if (auto* mission = std::get_if<MissionInput>(&input)) {
    processMission(*mission);
  }
}

void MonitorNode::processMission(const MissionInput& input) {
  for (const dds::PeerKey& gone : participant_->takePeersGone()) mission_gate_.participantGone(gone);
  const std::uint32_t seq = input.mission.header().seq();
  if (mission_writer_ == input.writer && seq <= mission_seq_) return;  // sent again to a re-created reader
  if (mission_gate_.admit(0, input.writer, std::chrono::steady_clock::now()) == dds::Admission::kRefused) {
    if (mission_gate_.firstRefusal(0, input.writer)) {
      std::fprintf(stderr, "swa_monitor: a mission from a second writer, refused as the agents refuse it\n");
    }
    return;
  }
  mission_writer_ = input.writer;
  mission_seq_ = seq;
  const std::variant<agent::MissionCommand, std::string> read = wire::missionCommandOf(input.mission);
  if (const auto* why = std::get_if<std::string>(&read)) {
    std::fprintf(stderr, "swa_monitor: a mission from the ground it cannot read (%s): not scored\n", why->c_str());
    return;
  }
  // What the agents can fly is theirs to say (their own limits); only what no agent flies is left out here.
  const agent::MissionCommand& command = std::get<agent::MissionCommand>(read);
  if (const auto why = agent::missionCommandProblem(command, agent::MissionConfig{}.max_speed_mps, 1e300)) {
    std::fprintf(stderr, "swa_monitor: a mission from the ground the agents do not fly (%s): not scored\n",
                 why->c_str());
    return;
  }
  run_.onMission(command);
  std::fprintf(stderr, "swa_monitor: mission %u from the ground: the run is scored against it from %.2f s\n", seq,
               run_.newestTruth() ? stampSeconds(*run_.newestTruth()) : 0.0);
}

void MonitorNode::publishNewMetrics() {
  if (options_.live != nullptr) options_.live->onMetrics(run_.series());
  if (options_.recording == nullptr) return;
  options_.recording->tick(std::chrono::steady_clock::now());
  if (options_.metrics != nullptr) options_.metrics->writeNew(run_.series());
}

void MonitorNode::showStatus(double wall_s, bool last) {
  if (options_.quiet) return;
  if (!pacer_.tty()) {
    if (pacer_.due(run_.status(), wall_s))
      std::fprintf(stderr, "swa_monitor: %s\n", formatStatus(run_.status()).c_str());
    return;
  }
  if (!last && !pacer_.due(run_.status(), wall_s)) return;
  const std::string line = formatStatus(run_.status());
  const std::size_t pad = status_width_ > line.size() ? status_width_ - line.size() : 0;
  std::fprintf(stderr, "\r%s%s%s", line.c_str(), std::string(pad, ' ').c_str(), last ? "\n" : "");
  std::fflush(stderr);
  status_width_ = line.size();
}

}  // namespace swa::monitor_node
