#pragma once
// When a crashed agent is started again: exponential back-off per agent, so a process that dies at start-up (bad
// host, missing library) is not restarted in a tight loop, with a cap on the number of restarts per run. Pure.

#include <algorithm>
#include <cmath>

namespace swa::launch {

class RestartPolicy {
 public:
  RestartPolicy(int max_restarts, double first_delay_s, double max_delay_s)
      : max_restarts_(max_restarts), first_delay_s_(first_delay_s), max_delay_s_(max_delay_s) {}

  // Whether an agent that has been restarted `restarts_so_far` times may be restarted once more.
  bool allowed(int restarts_so_far) const { return restarts_so_far < max_restarts_; }

  // Delay before restart number restarts_so_far + 1: first, 2 first, 4 first, ... capped at max.
  double delay(int restarts_so_far) const {
    const double d = first_delay_s_ * std::pow(2.0, static_cast<double>(std::max(0, restarts_so_far)));
    return std::min(d, max_delay_s_);
  }

 private:
  int max_restarts_;
  double first_delay_s_;
  double max_delay_s_;
};

}  // namespace swa::launch
