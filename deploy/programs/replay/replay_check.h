#pragma once
// swa_replay --check: the agent core re-run in-process on a recording's inputs, each UAV's commands compared with the
// ones its agent sent. The inputs go in the order swa_agent processes them in a lockstep run (by stamp; at equal
// stamps IMU, detections, GNSS: agent/node/sample_order.h), each IMU sample answered as swa_agent answers it, so with
// the recorded parameters every command comes out bit-identical: the recording becomes a regression test. With other
// parameters (--set agent.*) it shows where and by how much the commands change. No DDS entity.
//
// A realtime run may have processed a late detection after the next IMU sample; its check can then differ where
// that happened (lockstep runs are the reproducible ones).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "recorded_run.h"
#include "swa/agent/config.h"

namespace swa::replay {

struct CommandDifference {
  std::int64_t stamp_ns = 0;
  double recorded_vx = 0.0, recorded_vy = 0.0, recorded_yaw_rate = 0.0;
  double replayed_vx = 0.0, replayed_vy = 0.0, replayed_yaw_rate = 0.0;
};

struct UavCheck {
  int uav = 0;
  std::uint64_t inputs = 0;
  std::uint64_t undecodable = 0;  // input payloads the generated code could not decode: skipped
  std::uint64_t replayed = 0;     // commands the core produced
  std::uint64_t recorded = 0;     // commands in the recording
  // Replayed commands whose payload equals the recorded one of the same stamp, byte for byte.
  std::uint64_t identical = 0;
  std::uint64_t differing = 0;                 // same stamp, other bytes
  std::uint64_t not_recorded = 0;              // replayed, no recorded command of that stamp
  std::uint64_t not_replayed = 0;              // recorded, not produced by the replay
  double max_speed_difference_mps = 0.0;       // largest |replayed - recorded| velocity among the differing ones
  double max_yaw_rate_difference_radps = 0.0;  // and yaw rate
  std::optional<CommandDifference> first_difference;
  std::optional<std::int64_t> first_not_recorded_ns;  // stamp of the first replayed command the recording lacks

  bool identicalRun() const { return differing == 0 && not_recorded == 0 && not_replayed == 0 && replayed > 0; }
};

// Checks every UAV of `run` with the agent configuration `config`.
std::vector<UavCheck> checkRun(const RecordedRun& run, const agent::AgentConfig& config);

// One line per UAV and a verdict line, for the terminal.
std::string formatChecks(const std::vector<UavCheck>& checks);

}  // namespace swa::replay
