#include "latency_stats.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace swa::sim_node {

// ---- CommandLatencyTracker ----------------------------------------------------------------------------------------

double LatencyReport::lateFraction() const {
  return published ? static_cast<double>(late) / static_cast<double>(published) : 0.0;
}

double LatencyReport::missingFraction() const {
  return published ? static_cast<double>(missing) / static_cast<double>(published) : 0.0;
}

CommandLatencyTracker::CommandLatencyTracker(int uav_count, int window) : uav_count_(uav_count), window_(window) {
  if (uav_count < 0 || window < 1) throw std::invalid_argument("CommandLatencyTracker: bad UAV count or window");
  slots_.resize(static_cast<std::size_t>(uav_count) * static_cast<std::size_t>(window));
  newest_.resize(static_cast<std::size_t>(uav_count));
}

CommandLatencyTracker::Slot* CommandLatencyTracker::slot(int uav, std::uint32_t seq) {
  if (uav < 0 || uav >= uav_count_) return nullptr;
  const std::size_t k = static_cast<std::size_t>(uav) * static_cast<std::size_t>(window_) +
                        static_cast<std::size_t>(seq % static_cast<std::uint32_t>(window_));
  return &slots_[k];
}

void CommandLatencyTracker::published(int uav, std::uint32_t seq, std::int64_t stamp_ns, WallNs published_ns,
                                      std::optional<WallNs> due_ns) {
  Slot* s = slot(uav, seq);
  if (s == nullptr) return;
  if (s->used && !s->answered) ++missing_;  // evicted unanswered: `window` samples later, it is not coming
  *s = Slot{true, false, seq, stamp_ns, published_ns, due_ns.has_value(), due_ns.value_or(0), false};
  std::optional<std::uint32_t>& newest = newest_[static_cast<std::size_t>(uav)];
  // A newer sample means its predecessor's step was taken, whether or not stepTaken() said so: deadline as it was.
  if (newest && *newest != seq) {
    Slot* previous = slot(uav, *newest);
    if (previous->used && previous->seq == *newest) previous->step_taken = true;
  }
  newest = seq;
}

void CommandLatencyTracker::answered(int uav, std::uint32_t seq, std::int64_t stamp_ns, WallNs received_ns) {
  Slot* s = slot(uav, seq);
  if (s == nullptr || !s->used || s->seq != seq || s->stamp_ns != stamp_ns) {
    ++unmatched_;
    return;
  }
  if (s->answered) {
    ++duplicates_;
    return;
  }
  s->answered = true;
  histogram_.add(received_ns - s->published_ns);
  if (s->has_due && s->step_taken && received_ns > s->due_ns) ++late_;
}

bool CommandLatencyTracker::newestAnswered() const {
  for (int uav = 0; uav < uav_count_; ++uav) {
    const std::optional<std::uint32_t> seq = newest_[static_cast<std::size_t>(uav)];
    if (!seq) continue;
    const Slot& s = slots_[static_cast<std::size_t>(uav) * static_cast<std::size_t>(window_) +
                           static_cast<std::size_t>(*seq % static_cast<std::uint32_t>(window_))];
    if (s.used && s.seq == *seq && !s.answered) return false;
  }
  return true;
}

void CommandLatencyTracker::stepTaken(WallNs taken_ns) {
  for (int uav = 0; uav < uav_count_; ++uav) {
    const std::optional<std::uint32_t> seq = newest_[static_cast<std::size_t>(uav)];
    Slot* s = seq ? slot(uav, *seq) : nullptr;
    if (s == nullptr || !s->used || s->seq != *seq || s->step_taken) continue;
    s->step_taken = true;
    s->due_ns = std::max(s->due_ns, taken_ns);
  }
}

void CommandLatencyTracker::finish(WallNs now_ns) {
  for (Slot& s : slots_) {
    if (s.used && !s.answered && (!s.has_due || s.due_ns <= now_ns)) ++missing_;
    s.used = false;
  }
}

LatencyReport CommandLatencyTracker::report() const {
  LatencyReport r;
  r.answered = histogram_.count();
  r.late = late_;
  r.missing = missing_;
  r.published = r.answered + r.missing;
  r.duplicates = duplicates_;
  r.unmatched = unmatched_;
  r.p50_us = histogram_.quantileNs(0.50) * 1e-3;
  r.p99_us = histogram_.quantileNs(0.99) * 1e-3;
  r.max_us = histogram_.maxNs() * 1e-3;
  r.mean_us = histogram_.meanNs() * 1e-3;
  return r;
}

}  // namespace swa::sim_node
