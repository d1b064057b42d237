#pragma once
// The live status line on stderr: refreshed in place (\r) on a terminal, otherwise one line every 10 s of sim time
// so a log file stays readable.

#include <optional>
#include <string>

#include "live_run.h"

namespace swa::monitor_node {

// "t 12.3 s  d_NB 9.87 m  min sep 7.21 m  collisions 0  groups 1  agents 4/4 live" ("n/a" for an undefined value),
// or "waiting for ground truth" before the first step.
std::string formatStatus(const LiveStatus& status);

// Decides when to print: on a terminal at most every `tty_period_s` wall seconds, else whenever sim time enters a
// new `log_period_s` interval (the first step included).
class StatusPacer {
 public:
  explicit StatusPacer(bool tty, double tty_period_s = 0.25, double log_period_s = 10.0)
      : tty_(tty), tty_period_s_(tty_period_s), log_period_s_(log_period_s) {}
  bool due(const LiveStatus& status, double wall_s);
  bool tty() const { return tty_; }

 private:
  bool tty_;
  double tty_period_s_;
  double log_period_s_;
  std::optional<double> last_wall_s_;
  std::optional<long long> last_interval_;
};

}  // namespace swa::monitor_node
