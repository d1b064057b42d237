#pragma once
// How long this process itself did not run (SIGSTOP, a suspended VM, a starved host): the time between two
// consecutive checks beyond the longest gap the loop's own waits explain. The simulator moves its wall-clock
// deadlines (agent timeouts, realtime pacing) by it, so a stalled simulator does not declare its healthy agents dead
// for its own pause, nor race through the simulated time it missed; an agent does not blame a channel for what it
// did not hear while it did not run itself. Pure: the caller passes the time.

#include <chrono>

namespace swa::app {

class StallWatch {
 public:
  using Clock = std::chrono::steady_clock;

  // `max_gap`: the longest a healthy loop can take between checks (its longest wait plus slack).
  explicit StallWatch(Clock::duration max_gap) : max_gap_(max_gap) {}

  // The time lost since the previous check: (now - previous) - max_gap when that is positive, else zero. The first
  // check only starts the watch.
  Clock::duration check(Clock::time_point now) {
    Clock::duration lost = Clock::duration::zero();
    if (started_ && now - previous_ > max_gap_) lost = now - previous_ - max_gap_;
    started_ = true;
    previous_ = now;
    total_ += lost;
    if (lost > Clock::duration::zero()) ++stalls_;
    return lost;
  }

  // Starts measuring from `now`, whatever happened since the previous check (a wait the caller knows about).
  void restart(Clock::time_point now) {
    started_ = true;
    previous_ = now;
  }

  Clock::duration total() const { return total_; }
  int stalls() const { return stalls_; }

 private:
  Clock::duration max_gap_;
  bool started_ = false;
  Clock::time_point previous_{};
  Clock::duration total_ = Clock::duration::zero();
  int stalls_ = 0;
};

}  // namespace swa::app
