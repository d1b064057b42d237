#pragma once
// Realtime: the world steps on a wall-clock schedule (clock.speed simulated seconds per second) whatever the agents
// do; each UAV applies its newest setpoint, and an agent silent for the agent timeout is dead until it answers again.
// The clock starts once every agent has answered step 0 (a handshake), and a stall of the simulator itself moves the
// schedule with it.

#include <optional>
#include <vector>

#include "driver.h"

namespace swa::sim_node {

class RealtimeDriver : public Driver {
 public:
  explicit RealtimeDriver(const DriverContext& context);

  void run() override;
  bool alive(int uav) const override { return alive_[static_cast<std::size_t>(uav)]; }

 private:
  void handshake();
  void drain(Clock::duration wait);
  void collectLateAnswers(Clock::time_point until);  // after the last step: statistics only
  // How long after the last step's due time its answers are still waited for (counted late, not missing).
  static constexpr auto kLastAnswersGrace = std::chrono::milliseconds(200);

  std::vector<bool> alive_;
  std::vector<Clock::time_point> last_answer_;
  std::vector<std::optional<agent::StampNs>> last_applied_;
};

}  // namespace swa::sim_node
