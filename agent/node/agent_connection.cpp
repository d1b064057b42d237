// AgentNode's side of DDS: its participant and endpoints, and what tells it that they no longer reach its peers
// (a peer back after its lease whose endpoints did not re-match, what it is still waiting for, a twin). run() in
// agent_node.cpp decides from these when to re-create the participant.

#include "agent_node.h"

#include <chrono>
#include <cstdio>

#include <swa/msg/AgentStatePubSubTypes.h>
#include <swa/msg/ClockPubSubTypes.h>
#include <swa/msg/DetectionsPubSubTypes.h>
#include <swa/msg/GnssFixPubSubTypes.h>
#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/SensorFramePubSubTypes.h>
#include <swa/msg/SwarmMissionPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>
#include <swa/ros/Detection3DArrayPubSubTypes.h>
#include <swa/ros/PoseWithCovarianceArrayStampedPubSubTypes.h>
#include <swa/ros/TwistStampedPubSubTypes.h>

#include "swa/dds/deployment.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"
#include "swa/wire/ros_detections.h"

namespace swa::agent_node {
namespace {

// No IMU sample this long after connecting: the agent says once what has matched (a simulator not started yet, or
// a discovery that failed).
constexpr auto kWaitReport = std::chrono::seconds(5);
// After a peer came back from an expired lease, how long its endpoints get to re-match ours before the participant
// is re-created (peer_book.h). Re-matching takes milliseconds when it works; the lockstep simulator waits 2 s (its
// default agent timeout) for an answer.
constexpr auto kRematchWait = std::chrono::milliseconds(500);

}  // namespace

void AgentNode::connect() {
  participant_ = std::make_unique<dds::Participant>("swa_agent_" + std::to_string(id_), domain_id_, profiles_file_);
  handshake_.connected(std::chrono::steady_clock::now());
  // Writers first: a command must have somewhere to go as soon as the first IMU sample is processed.
  cmd_writer_ =
      participant_->writer<msg::VelocitySetpointPubSubType>(dds::topics::cmdVel(id_), dds::qos::kCommandWriter);
  state_writer_ = participant_->writer<msg::AgentStatePubSubType>(dds::topics::state(id_), dds::qos::kStateWriter);
  if (participant_->wireNames().naming == dds::Naming::kRos2) {
    twist_writer_ = participant_->writer<geometry_msgs::msg::TwistStampedPubSubType>(dds::topics::cmdVelStamped(id_),
                                                                                     dds::qos::kCommandWriter);
  }
  imu_reader_ = participant_->reader<msg::ImuPubSubType>(dds::topics::imu(id_), dds::qos::kSensorReader,
                                                         [this](msg::Imu&& m) { onInput(Input(std::move(m))); });
  switch (agent_.config().sensor.input) {
    case agent::DetectionInput::kSwa:
      det_reader_ = participant_->reader<msg::DetectionsPubSubType>(
          dds::topics::detections(id_), dds::qos::kDetectionsGnssReader,
          [this](msg::Detections&& m) { onInput(Input(std::move(m))); });
      break;
    case agent::DetectionInput::kVisionMsgs:
      vision_reader_ = participant_->reader<vision_msgs::msg::Detection3DArrayPubSubType>(
          dds::topics::visionDetections(id_), dds::qos::kForeignDetectionsReader,
          [this](vision_msgs::msg::Detection3DArray&& m) { onForeign(wire::foreignOf(m)); });
      break;
    case agent::DetectionInput::kUvdar:
      uvdar_reader_ = participant_->reader<mrs_msgs::msg::PoseWithCovarianceArrayStampedPubSubType>(
          dds::topics::uvdarPoses(id_), dds::qos::kForeignDetectionsReader,
          [this](mrs_msgs::msg::PoseWithCovarianceArrayStamped&& m) { onForeign(wire::foreignOf(m)); });
      break;
  }
  gnss_reader_ =
      participant_->reader<msg::GnssFixPubSubType>(dds::topics::gnss(id_), dds::qos::kDetectionsGnssReader,
                                                   [this](msg::GnssFix&& m) { onInput(Input(std::move(m))); });
  if (agent_.config().sensor.input == agent::DetectionInput::kSwa &&
      participant_->wireNames().naming == dds::Naming::kSwa) {
    frame_reader_ = participant_->reader<msg::SensorFramePubSubType>(
        dds::topics::sensors(id_), dds::qos::kFrameReader, [this](msg::SensorFrame&& m) { onFrame(std::move(m)); });
  }
  mission_reader_ = participant_->readerWithOrigin<msg::SwarmMissionPubSubType>(
      dds::topics::kMission, dds::qos::kMissionReader,
      [this](msg::SwarmMission&& m, const dds::WriterGuid& writer) { onMission(std::move(m), writer); });
  clock_reader_ = participant_->reader<msg::ClockPubSubType>(
      dds::topics::kClock, dds::qos::kClockWatchReader, [this](msg::Clock&& m) {
        const std::lock_guard<std::mutex> lock(mutex_);
        world_pause_.tick(m.step(), std::chrono::steady_clock::now());
      });
  dds::sayOwnSharedMemoryPorts("swa_agent " + std::to_string(id_));
  deaf_ports_.reset();
  imu_silence_.restart();
  detections_silence_.restart();
  peers_back_ = 0;
  peer_back_at_.reset();
  matched_once_ = {};
  connected_at_ = std::chrono::steady_clock::now();
  waiting_reported_ = false;
}

AgentNode::Matched AgentNode::matchedNow() const {
  const int detections = det_reader_      ? det_reader_.matched()
                         : vision_reader_ ? vision_reader_.matched()
                                          : uvdar_reader_.matched();
  // A writer of frames writes all three inputs.
  const int frames = frame_reader_ ? frame_reader_.matched() : 0;
  return {cmd_writer_.matched(), imu_reader_.matched() + frames, detections + frames, gnss_reader_.matched() + frames};
}

std::string AgentNode::detectionsTopic() const {
  switch (agent_.config().sensor.input) {
    case agent::DetectionInput::kVisionMsgs:
      return dds::topics::visionDetections(id_);
    case agent::DetectionInput::kUvdar:
      return dds::topics::uvdarPoses(id_);
    case agent::DetectionInput::kSwa:
      break;
  }
  return dds::topics::detections(id_);
}

void AgentNode::reportWaiting(const Matched& matched) {
  // A silent agent that never got a sample looks exactly like one that is fine: say once what it is waiting for.
  if (waiting_reported_ || stats_.imu > 0 || std::chrono::steady_clock::now() - connected_at_ < kWaitReport) return;
  waiting_reported_ = true;
  const std::string frames = frame_reader_ ? " (each counting the " + std::to_string(frame_reader_.matched()) + " of " +
                                                 dds::topics::sensors(id_) + ")"
                                           : std::string();
  std::fprintf(stderr,
               "swa_agent %d: no IMU sample %.0f s after connecting; matched: %d reader(s) of %s, %d writer(s) of %s, "
               "%d of %s, %d of %s%s\n",
               id_, std::chrono::duration<double>(kWaitReport).count(), matched[0], dds::topics::cmdVel(id_).c_str(),
               matched[1], dds::topics::imu(id_).c_str(), matched[2], detectionsTopic().c_str(), matched[3],
               dds::topics::gnss(id_).c_str(), frames.c_str());
  // What a person who started the agent by hand needs to know: what it waits for, and where. A swarm started by
  // swa_launch is a partition of its own, which an agent outside it never sees.
  const std::string swarm = dds::resolveDeployment().swarm;
  std::fprintf(
      stderr,
      "swa_agent %d: it waits for a simulator (swa_sim) or an autopilot bridge writing UAV %d's samples on DDS "
      "domain %d, %s; a swa_launch run is a swarm of its own (named on its first line) unless launched with "
      "--swarm none: to join one, start this agent with that SWA_SWARM\n",
      id_, id_, domain_id_,
      swarm.empty() ? "in the default swarm (SWA_SWARM unset)" : ("in swarm " + swarm + " (SWA_SWARM)").c_str());
}

std::optional<std::string> AgentNode::endpointsLostAfterPeerReturn(const Matched& matched) {
  // A peer that went silent beyond its lease and never dropped us: Fast DDS 2.9 sometimes does not re-send all its
  // endpoints (peer_book.h), and a UAV loses its sensors or its commands for good. Only then, and only if one of our
  // endpoints that had matched is still unmatched a moment later: a peer lost and back under packet loss is no
  // reason to reconnect, nor one that returns while our endpoints are still being discovered (a starved host).
  const std::array<std::pair<std::string, bool>, 4> endpoints{{
      {dds::topics::cmdVel(id_), matched[0] >= 1},
      {dds::topics::imu(id_), matched[1] >= 1},
      {detectionsTopic(), matched[2] >= 1},
      {dds::topics::gnss(id_), matched[3] >= 1},
  }};
  for (std::size_t k = 0; k < endpoints.size(); ++k) matched_once_[k] = matched_once_[k] || endpoints[k].second;
  const dds::Participant::PeersBack back = participant_->peersBackAfterLease();
  const auto now = std::chrono::steady_clock::now();
  if (back.count != peers_back_) {
    peers_back_ = back.count;
    peer_back_at_ = now;
    peer_back_name_ = back.last_name;
    peer_back_key_ = back.last_key;
  }
  if (!peer_back_at_ || now - *peer_back_at_ < kRematchWait) return std::nullopt;
  peer_back_at_.reset();
  std::string lost;
  for (std::size_t k = 0; k < endpoints.size(); ++k) {
    if (matched_once_[k] && !endpoints[k].second) lost += " " + endpoints[k].first;
  }
  if (!lost.empty()) {
    return "participant " + peer_back_name_ +
           " came back after its DDS lease expired and these did not re-match:" + lost;
  }
  // The reader of our commands may have dropped us while it was silent and not learnt our writer again: it looks
  // matched from here and hears nothing (CI: the simulator stopped 5 s, one agent declared dead for the rest of the
  // run). Nothing on this side shows it, so its return is reason enough.
  if (participant_->readBy(cmd_writer_, peer_back_key_)) {
    return "participant " + peer_back_name_ + ", the reader of " + dds::topics::cmdVel(id_) +
           ", came back after its DDS lease expired and may not know our writer any more";
  }
  return std::nullopt;
}

void AgentNode::refuseAsTwin() {
  const std::optional<dds::Peer> twin = participant_->twin();
  const std::string swarm = twin && !twin->card->swarm.empty() ? "swarm " + twin->card->swarm : "the default swarm";
  std::fprintf(stderr,
               "swa_agent %d: REFUSING to run: another swa_agent %d (pid %ld on host %s) was already running in %s on "
               "domain %d; two agents for one UAV would both command it. Stop one of them, or give this one another "
               "--id or SWA_SWARM.\n",
               id_, id_, twin ? twin->card->pid : 0L, twin ? twin->card->host.c_str() : "?", swarm.c_str(), domain_id_);
  participant_.reset();
}

void AgentNode::noteYoungerTwins() {
  for (const dds::Peer& twin : participant_->takeYoungerTwins()) {
    std::fprintf(stderr,
                 "swa_agent %d: a second swa_agent %d (pid %ld on host %s) joined this swarm; it started later and "
                 "must refuse to run (if it keeps commanding UAV %d, stop it)\n",
                 id_, id_, twin.card->pid, twin.card->host.c_str(), id_);
  }
}

}  // namespace swa::agent_node
