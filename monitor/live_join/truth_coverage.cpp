#include "truth_coverage.h"

namespace swa::monitor_node {

void TruthCoverage::add(agent::StampNs stamp_ns) {
  const agent::StampNs previous = started_ ? last_ns_ : 0;
  if (started_ && stamp_ns <= last_ns_) return;
  agent::StampNs gap = 0;
  if (__builtin_sub_overflow(stamp_ns, previous, &gap) || gap > max_gap_ns_) {
    missed_.push_back({static_cast<double>(previous) * 1e-9, static_cast<double>(stamp_ns) * 1e-9});
  }
  started_ = true;
  last_ns_ = stamp_ns;
}

double TruthCoverage::missedSeconds() const {
  double s = 0.0;
  for (const MissedSpan& m : missed_) s += m.to_s - m.from_s;
  return s;
}

}  // namespace swa::monitor_node
