#pragma once
// Tells a lockstep run that waits for someone else from a broken channel. In lockstep the simulator publishes no
// step until every live agent has answered the last one, and waits up to its startup timeout (60 s) for an agent's
// first answer: meanwhile every other agent's inputs stop with their writers matched, which is what the silence
// watches (silence_watch.h) take for a broken channel. Seen in a secure launch through PX4: the simulator waited 60 s
// at step 0 for one agent, the three others re-created their participants every 6 s throughout (8 times each), each
// re-creation cost new handshakes on a loaded host, and one agent ended with no detection channel and its UAV on
// failsafe.
//
// While it waits, the simulator sends the clock tick of the step it is on again, once a second (lockstep_driver.cpp);
// a running simulator never sends a step twice. So a tick heard twice means the world waits, and a silence then owes
// nothing. A broken channel still shows: ticks that stop too (the agent's own port gone deaf: nothing arrives), or
// ticks that advance while the IMU stays silent. Pure: the caller supplies the times.

#include <chrono>
#include <cstdint>
#include <optional>

namespace swa::agent_node {

class WorldPause {
 public:
  using Clock = std::chrono::steady_clock;
  // The simulator repeats a waiting step every second; a repeat this recent still counts.
  static constexpr std::chrono::milliseconds kRepeatWindow{2500};

  // A clock tick of step `step` arrived at `now`.
  void tick(std::uint64_t step, Clock::time_point now) {
    if (last_step_ && *last_step_ == step) repeated_at_ = now;
    last_step_ = step;
  }

  // Whether the simulator said within kRepeatWindow that it waits on its step.
  bool waiting(Clock::time_point now) const { return repeated_at_ && now - *repeated_at_ < kRepeatWindow; }

 private:
  std::optional<std::uint64_t> last_step_;
  std::optional<Clock::time_point> repeated_at_;
};

}  // namespace swa::agent_node
