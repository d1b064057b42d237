#include "swa/agent/stream_clock.h"

#include <algorithm>

namespace swa::agent {

StreamClock::StreamClock(StampNs max_jump_ns, int resync_samples)
    : max_jump_ns_(max_jump_ns), resync_samples_(resync_samples) {}

bool StreamClock::follows(StampNs previous, StampNs next) const {
  StampNs ahead = 0;
  if (next <= previous || __builtin_sub_overflow(next, previous, &ahead)) return false;
  return ahead <= max_jump_ns_;
}

bool StreamClock::atPeriod(StampNs previous, StampNs next) const {
  if (!follows(previous, next)) return false;
  if (period_ns_ <= 0.0) return true;
  const double step = static_cast<double>(next - previous);
  return step >= 0.5 * period_ns_ && step <= 2.0 * period_ns_;
}

StreamClock::Verdict StreamClock::check(StampNs stamp_ns) {
  if (!started_ || follows(last_ns_, stamp_ns)) {
    if (started_) {
      // Running mean over ~10 steps, each clipped to a factor 2 of the mean: it follows a change of rate within a
      // few dozen samples, while one bogus or late sample moves it by 10 % at most.
      const double step = static_cast<double>(stamp_ns - last_ns_);
      period_ns_ = period_ns_ <= 0.0
                       ? step
                       : period_ns_ + 0.1 * (std::clamp(step, 0.5 * period_ns_, 2.0 * period_ns_) - period_ns_);
    }
    started_ = true;
    last_ns_ = stamp_ns;
    candidate_count_ = 0;
    return Verdict::kAccept;
  }
  candidate_count_ = (candidate_count_ > 0 && atPeriod(candidate_last_ns_, stamp_ns)) ? candidate_count_ + 1 : 1;
  candidate_last_ns_ = stamp_ns;
  if (candidate_count_ >= resync_samples_) {
    last_ns_ = stamp_ns;
    candidate_count_ = 0;
    ++resyncs_;
    return Verdict::kResync;
  }
  return stamp_ns <= last_ns_ ? Verdict::kOutOfOrder : Verdict::kFuture;
}

void StreamClock::resume(StampNs stamp_ns) {
  started_ = true;
  last_ns_ = stamp_ns;
  candidate_count_ = 0;
}

}  // namespace swa::agent
