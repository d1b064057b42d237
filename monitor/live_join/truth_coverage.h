#pragma once
// Which part of the run the monitor saw: the truth samples it scored, against the run's start (sim time 0) and
// against each other. A monitor that started late (restarted after a crash, or by hand), or lost truth for a while,
// must say so in its verdict instead of scoring what it saw as the whole run. Pure; stamps in, spans out.

#include <cstdint>
#include <utility>
#include <vector>

#include "swa/agent/samples.h"
#include "swa/run_record/verdict.h"

namespace swa::monitor_node {

using record::MissedSpan;

class TruthCoverage {
 public:
  // Truth is published every 100 ms of sim time: a gap of more than `max_gap_s` (and a first sample later than it)
  // is time the monitor did not see.
  explicit TruthCoverage(double max_gap_s = 1.0) : max_gap_ns_(static_cast<agent::StampNs>(max_gap_s * 1e9)) {}

  // A scored truth sample; stamps not after the previous one are ignored.
  void add(agent::StampNs stamp_ns);

  const std::vector<MissedSpan>& missed() const { return missed_; }
  double missedSeconds() const;

 private:
  agent::StampNs max_gap_ns_;
  bool started_ = false;
  agent::StampNs last_ns_ = 0;
  std::vector<MissedSpan> missed_;
};

}  // namespace swa::monitor_node
