#pragma once
// Lockstep bookkeeping of swa_sim: which agents the simulator waits for at the current step, which answers to
// apply, and who is dead. Pure (no DDS, no clock): the node decides when the agent timeout has passed and calls
// expire().
//
// Per step: begin(stamps) with the IMU stamp published to each UAV (nullopt: no IMU this step, nothing to wait for).
// An answer is a command whose answered_stamp_ns echoes such a stamp.
//   - live agent, answer to this step's IMU        -> kApply, the agent is done for this step;
//   - live agent, anything else (older, duplicate)  -> kIgnore;
//   - dead agent, answer to this or the previous step's IMU -> kRejoin (apply it; the agent is live again and
//     waited for from the next step on; it is done for this step if it answered this step);
//   - dead agent, older answer                      -> kIgnore; but if it answers a sample sent since it was
//     declared dead, further on than any answer that did so before, it is alive and catching up: it is waited for
//     (one agent timeout) like a live agent, so that it can reach the current step even when nobody else is alive
//     and the steps would otherwise race ahead of it.
// complete(): every live or catching-up agent with an IMU sample this step has answered. expire(): marks the live
// agents still missing as dead and returns them; a catching-up agent still missing is left dead without a new event
// (until it makes progress again). waitingForNewcomer(): one of the missing agents has never answered yet (it may
// still be discovering the simulator: the node then waits up to the startup timeout, not the agent timeout).

#include <optional>
#include <vector>

#include "swa/agent/samples.h"

namespace swa::sim_node {

enum class Verdict { kApply, kRejoin, kIgnore };

class LockstepTracker {
 public:
  explicit LockstepTracker(int uav_count);

  void begin(const std::vector<std::optional<agent::StampNs>>& imu_stamps);
  Verdict onAnswer(int uav, agent::StampNs answered_stamp_ns);
  bool complete() const;
  std::vector<int> expire();

  bool alive(int uav) const { return alive_.at(static_cast<std::size_t>(uav)); }
  int aliveCount() const;
  int uavCount() const { return static_cast<int>(alive_.size()); }
  std::vector<int> waitingFor() const;  // live agents not yet answered this step
  bool waitingForNewcomer() const;

 private:
  std::vector<bool> alive_;
  std::vector<bool> answered_;
  std::vector<bool> ever_answered_;
  std::vector<std::optional<agent::StampNs>> current_;
  std::vector<std::optional<agent::StampNs>> previous_;
  std::vector<std::optional<agent::StampNs>> dead_since_;    // the stamp it did not answer
  std::vector<std::optional<agent::StampNs>> caught_up_to_;  // the newest answer that earned a wait
  std::vector<bool> catching_up_;

  bool waitedFor(std::size_t i) const { return (alive_[i] || catching_up_[i]) && current_[i] && !answered_[i]; }
};

}  // namespace swa::sim_node
