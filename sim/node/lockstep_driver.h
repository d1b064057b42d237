#pragma once
// Lockstep: every step's sensor samples are published, then the world waits for each live agent's answer to its IMU
// sample (lockstep_tracker.h) up to the agent timeout, and for the acknowledgment of its detections and GNSS fix (and,
// every tenth step, the monitors' of the clock), before it steps. Deterministic: the same scenario and seed give the
// same run as the in-process loop (deploy/programs/batch).

#include <functional>
#include <vector>

#include "driver.h"
#include "lockstep_tracker.h"

namespace swa::sim_node {

class LockstepDriver : public Driver {
 public:
  explicit LockstepDriver(const DriverContext& context);

  void run() override;
  bool alive(int uav) const override { return lockstep_.alive(uav); }

 private:
  void drain(Clock::duration wait);
  // Moves `deadline` by any stall of the simulator seen while waiting.
  void awaitSensorAcks(Clock::time_point& deadline);
  // Polls `acknowledged(wait_s)` until it holds (true) or `deadline` passes (false), moving `deadline` the same way.
  bool awaitAck(Clock::time_point& deadline, const std::function<bool(double)>& acknowledged);

  LockstepTracker lockstep_;
};

}  // namespace swa::sim_node
