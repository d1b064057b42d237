#pragma once
// swa_replay without --check: a recording's inputs re-published on DDS (replay_options.cpp explains what and how),
// as the process role "swa_replay". With --lockstep, the replayed agents' answers are compared with the recorded
// commands (byte for byte, by stamp).

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <utility>

#include "recorded_run.h"
#include "replay_options.h"
#include "swa/app/program.h"
#include "swa/dds/participant.h"

namespace swa::replay {

class ReplayNode : public app::Role {
 public:
  // Creates the participant and its endpoints; throws swa::dds::DdsError.
  ReplayNode(RecordedRun run, const ReplayOptions& options, int domain_id);
  ~ReplayNode() override;
  int run() override;
  void stop() override;

 private:
  struct Writers {
    dds::Writer<dds::Payload> imu, detections, gnss;
  };
  void waitForReaders();
  // Publishes the samples of one stamp; returns the UAVs whose IMU sample of that stamp went out.
  void onCommand(int uav, dds::Payload&& payload);
  bool waitForAnswers(std::int64_t stamp_ns, const std::set<int>& uavs);
  // --lockstep: until the agents of `uavs` acknowledged the detections and GNSS fixes just written.
  void waitForAcknowledgments(const std::set<int>& uavs);
  int report();

  RecordedRun run_;
  const ReplayOptions options_;
  std::atomic<bool> stop_{false};

  std::mutex mutex_;
  std::condition_variable answered_;
  std::map<std::pair<int, std::int64_t>, dds::Payload> answers_;  // (uav, stamp) -> the agent's command
  std::uint64_t answers_missed_ = 0;                              // --lockstep: waits that timed out
  std::uint64_t unacknowledged_ = 0;  // --lockstep: stamps whose detections / GNSS were not acknowledged in time

  std::unique_ptr<dds::Participant> participant_;
  std::map<int, Writers> writers_;
  std::map<std::string, dds::Writer<dds::Payload>> world_writers_;
};

}  // namespace swa::replay
