#include "replay_node.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>
#include <tuple>
#include <vector>

#include <swa/msg/ClockPubSubTypes.h>
#include <swa/msg/DetectionsPubSubTypes.h>
#include <swa/msg/GnssFixPubSubTypes.h>
#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/ScenarioEventPubSubTypes.h>
#include <swa/msg/SwarmTruthPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>

#include "swa/dds/options.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"
#include "swa/recording/recording.h"

namespace swa::replay {
namespace {

using Clock = std::chrono::steady_clock;
// Longest wait for one agent's answer in --lockstep (the simulator's --agent-timeout-s default).
constexpr auto kAnswerTimeout = std::chrono::seconds(2);
// After the last sample, how long answers may still come in.
constexpr auto kLastAnswersWait = std::chrono::seconds(2);

// One thing to publish, on the merged timeline of every UAV's inputs and the world's topics.
struct Item {
  std::int64_t time_ns;
  int rank;  // at equal times: the world first (the simulator publishes truth and events of a step before the
             // next step's sensors), then detections and GNSS, then the IMU sample, as the simulator writes them in
             // lockstep (sensor_ports.cpp)
  std::uint64_t order;
  int uav;             // -1: a world topic
  InputSample* input;  // or
  WorldSample* world;
};

}  // namespace

ReplayNode::ReplayNode(RecordedRun run, const ReplayOptions& options, int domain_id)
    : run_(std::move(run)), options_(options) {
  participant_ = std::make_unique<dds::Participant>("swa_replay", domain_id, dds::resolveProfilesFile());
  namespace topics = dds::topics;
  for (const auto& [uav, recording] : run_.uavs) {
    // The simulator's writer profiles: the agents' readers match them as they matched the simulator.
    Writers w;
    w.detections =
        participant_->rawWriter<msg::DetectionsPubSubType>(topics::detections(uav), dds::qos::kDetectionsGnssWriter);
    w.gnss = participant_->rawWriter<msg::GnssFixPubSubType>(topics::gnss(uav), dds::qos::kDetectionsGnssWriter);
    w.imu = participant_->rawWriter<msg::ImuPubSubType>(topics::imu(uav), dds::qos::kSensorWriter);
    writers_[uav] = w;
    if (options_.lockstep) {
      participant_->rawReader<msg::VelocitySetpointPubSubType>(
          topics::cmdVel(uav), dds::qos::kCommandReader,
          [this, id = uav](dds::RawSample&& s) { onCommand(id, std::move(s.payload)); });
    }
  }
  if (!options_.uav) {
    world_writers_[topics::kTruth] =
        participant_->rawWriter<msg::SwarmTruthPubSubType>(topics::kTruth, dds::qos::kTruthWriter);
    world_writers_[topics::kEvents] =
        participant_->rawWriter<msg::ScenarioEventPubSubType>(topics::kEvents, dds::qos::kEventWriter);
    world_writers_[topics::kClock] =
        participant_->rawWriter<msg::ClockPubSubType>(topics::kClock, dds::qos::kClockWriter);
  }
}

ReplayNode::~ReplayNode() { participant_.reset(); }

void ReplayNode::stop() {
  stop_ = true;
  answered_.notify_all();
}

void ReplayNode::onCommand(int uav, dds::Payload&& payload) {
  const std::optional<recording::PayloadStamp> stamp = recording::payloadStamp(payload.data(), payload.size());
  if (!stamp) return;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    answers_.emplace(std::make_pair(uav, static_cast<std::int64_t>(stamp->stamp_ns)), std::move(payload));
  }
  answered_.notify_all();
}

void ReplayNode::waitForReaders() {
  const auto until =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options_.wait_s));
  while (!stop_) {
    std::vector<int> waiting;
    for (auto& [uav, w] : writers_) {
      if (w.imu.matched() < 1) waiting.push_back(uav);
    }
    // A monitor's truth reader appears once it has matched every agent (monitor_node.cpp): wait for it too.
    const bool truth_waiting =
        world_writers_.count(dds::topics::kTruth) > 0 && world_writers_.at(dds::topics::kTruth).matched() < 1;
    if (waiting.empty() && !truth_waiting) return;
    if (Clock::now() >= until) {
      std::string list;
      for (const int uav : waiting) list += " " + std::to_string(uav);
      std::fprintf(stderr, "swa_replay: no IMU reader of UAV(s)%s%s after %.0f s; replaying anyway\n", list.c_str(),
                   truth_waiting ? " and no truth reader" : "", options_.wait_s);
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

bool ReplayNode::waitForAnswers(std::int64_t stamp_ns, const std::set<int>& uavs) {
  std::unique_lock<std::mutex> lock(mutex_);
  const auto all_in = [&] {
    return stop_ || std::all_of(uavs.begin(), uavs.end(),
                                [&](int uav) { return answers_.count(std::make_pair(uav, stamp_ns)) > 0; });
  };
  if (answered_.wait_for(lock, kAnswerTimeout, all_in)) return true;
  ++answers_missed_;
  return false;
}

void ReplayNode::waitForAcknowledgments(const std::set<int>& uavs) {
  // The agent orders its inputs by stamp (sample_order.h): the commands are the recorded ones only if this stamp's
  // detections and GNSS fix are in its queue before the next stamp's IMU sample. DDS orders samples per topic, not
  // across topics, and a lost sample is repaired only after the next heartbeat (idl/runtime/dds/profiles.xml), so
  // the next IMU sample could overtake it: wait until the agent has acknowledged them, as the simulator does.
  const double wait_s = std::chrono::duration<double>(kAnswerTimeout).count();
  for (const int uav : uavs) {
    if (stop_) return;
    Writers& w = writers_.at(uav);
    if (!w.detections.waitForAcknowledgments(wait_s) || !w.gnss.waitForAcknowledgments(wait_s)) ++unacknowledged_;
  }
}

int ReplayNode::run() {
  std::vector<Item> items;
  for (auto& [uav, recording] : run_.uavs) {
    for (InputSample& in : recording.inputs) {
      const int rank = in.input == Input::kDetections ? 1 : in.input == Input::kGnss ? 2 : 3;
      items.push_back({in.stamp_ns, rank, in.order, uav, &in, nullptr});
    }
  }
  for (WorldSample& w : run_.world) {
    items.push_back({static_cast<std::int64_t>(w.log_time_ns), 0, w.order, -1, nullptr, &w});
  }
  std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
    return std::tie(a.time_ns, a.rank, a.order) < std::tie(b.time_ns, b.rank, b.order);
  });
  waitForReaders();
  std::fprintf(stderr, "swa_replay: replaying %zu samples of %zu UAV(s)%s\n", items.size(), run_.uavs.size(),
               options_.lockstep ? " in lockstep" : "");

  const auto t0 = Clock::now();
  const std::int64_t first_ns = items.empty() ? 0 : items.front().time_ns;
  std::uint64_t write_failures = 0;
  for (std::size_t i = 0; i < items.size() && !stop_;) {
    const std::int64_t stamp = items[i].time_ns;
    if (options_.speed > 0.0) {
      std::this_thread::sleep_until(t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                                             static_cast<double>(stamp - first_ns) * 1e-9 / options_.speed)));
    }
    std::set<int> imu_uavs, side_uavs;
    for (; i < items.size() && items[i].time_ns == stamp; ++i) {
      const Item& it = items[i];
      bool ok = true;
      if (it.world != nullptr) {
        ok = world_writers_.at(it.world->topic).write(it.world->payload);
      } else {
        Writers& w = writers_.at(it.uav);
        dds::Payload& payload = it.input->payload;
        if (it.input->input == Input::kImu) {
          ok = w.imu.write(payload);
          imu_uavs.insert(it.uav);
        } else {
          ok = (it.input->input == Input::kDetections ? w.detections : w.gnss).write(payload);
          side_uavs.insert(it.uav);
        }
      }
      if (!ok) ++write_failures;
    }
    if (options_.lockstep && !imu_uavs.empty()) waitForAnswers(stamp, imu_uavs);
    if (options_.lockstep) waitForAcknowledgments(side_uavs);
  }
  if (options_.lockstep && !stop_) std::this_thread::sleep_for(kLastAnswersWait);
  if (write_failures > 0) {
    std::fprintf(stderr, "swa_replay: %llu samples refused by DDS\n", static_cast<unsigned long long>(write_failures));
  }
  return report();
}

int ReplayNode::report() {
  if (!options_.lockstep) {
    std::printf("swa_replay: %s\n", stop_ ? "interrupted" : "replayed");
    return kExitOk;
  }
  // The answers against the recorded commands of the same stamp.
  const std::lock_guard<std::mutex> lock(mutex_);
  bool all_identical = !stop_;
  for (const auto& [uav, recording] : run_.uavs) {
    std::map<std::int64_t, const dds::Payload*> recorded;
    for (const dds::Payload& p : recording.commands) {
      if (auto stamp = recording::payloadStamp(p.data(), p.size())) recorded.emplace(stamp->stamp_ns, &p);
    }
    std::uint64_t answers = 0, identical = 0, differing = 0, unrecorded = 0;
    for (const auto& [key, payload] : answers_) {
      if (key.first != uav) continue;
      ++answers;
      const auto it = recorded.find(key.second);
      if (it == recorded.end()) {
        ++unrecorded;
      } else if (*it->second == payload) {
        ++identical;
      } else {
        ++differing;
      }
    }
    const std::uint64_t unanswered = recorded.size() - std::min<std::uint64_t>(recorded.size(), identical + differing);
    std::printf(
        "swa_replay: uav %d: %llu answers, %llu recorded commands: %llu identical, %llu differ, %llu not "
        "recorded, %llu not answered\n",
        uav, static_cast<unsigned long long>(answers), static_cast<unsigned long long>(recorded.size()),
        static_cast<unsigned long long>(identical), static_cast<unsigned long long>(differing),
        static_cast<unsigned long long>(unrecorded), static_cast<unsigned long long>(unanswered));
    all_identical = all_identical && differing == 0 && unrecorded == 0 && unanswered == 0 && answers > 0;
  }
  if (unacknowledged_ > 0) {
    std::printf(
        "swa_replay: %llu steps whose detections or GNSS fix were not acknowledged within %lld s (the "
        "next IMU sample may have overtaken them)\n",
        static_cast<unsigned long long>(unacknowledged_),
        static_cast<long long>(std::chrono::duration_cast<std::chrono::seconds>(kAnswerTimeout).count()));
  }
  if (answers_missed_ > 0) {
    std::printf("swa_replay: %llu steps without every answer within %lld s\n",
                static_cast<unsigned long long>(answers_missed_),
                static_cast<long long>(std::chrono::duration_cast<std::chrono::seconds>(kAnswerTimeout).count()));
  }
  std::printf("swa_replay: %s\n",
              all_identical ? "IDENTICAL: every answer equals the recorded command" : "DIFFERENT: see the lines above");
  return all_identical ? kExitOk : kExitDifferent;
}

}  // namespace swa::replay
