#include "latency_stats.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace swa::sim_node {

// ---- LogHistogram -------------------------------------------------------------------------------------------------

double LogHistogram::relativeResolution() { return std::pow(10.0, 0.5 / kBinsPerDecade) - 1.0; }

LogHistogram::LogHistogram() : bins_(static_cast<std::size_t>(kBins + 2), 0) {}

void LogHistogram::add(WallNs value_ns) {
  const WallNs v = std::max<WallNs>(value_ns, 0);
  const auto x = static_cast<double>(v);
  int bin = 0;
  if (x >= kHighNs) {
    bin = kBins + 1;
  } else if (x >= kLowNs) {
    bin = 1 + std::min(kBins - 1, static_cast<int>(std::log10(x / kLowNs) * kBinsPerDecade));
  }
  ++bins_[static_cast<std::size_t>(bin)];
  ++count_;
  sum_ns_ += x;
  min_ns_ = std::min(min_ns_, v);
  max_ns_ = std::max(max_ns_, v);
}

void LogHistogram::merge(const LogHistogram& other) {
  for (std::size_t b = 0; b < bins_.size(); ++b) bins_[b] += other.bins_[b];
  count_ += other.count_;
  sum_ns_ += other.sum_ns_;
  min_ns_ = std::min(min_ns_, other.min_ns_);
  max_ns_ = std::max(max_ns_, other.max_ns_);
}

double LogHistogram::binCentreNs(int bin) const {
  // Bin b (1-based) spans [kLow 10^((b-1)/B), kLow 10^(b/B)); its geometric centre is kLow 10^((b-0.5)/B).
  return kLowNs * std::pow(10.0, (static_cast<double>(bin) - 0.5) / kBinsPerDecade);
}

double LogHistogram::quantileNs(double q) const {
  if (count_ == 0) return std::nan("");
  q = std::clamp(q, 0.0, 1.0);
  const auto rank = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(count_))));
  if (rank == 1) return minNs();
  if (rank >= count_) return maxNs();
  std::uint64_t cumulative = 0;
  for (int b = 0; b < kBins + 2; ++b) {
    cumulative += bins_[static_cast<std::size_t>(b)];
    if (cumulative < rank) continue;
    if (b == 0) return minNs();           // below the range: the best we know is the smallest value
    if (b == kBins + 1) return maxNs();   // above the range
    return std::clamp(binCentreNs(b), minNs(), maxNs());
  }
  return maxNs();
}

double LogHistogram::minNs() const { return count_ ? static_cast<double>(min_ns_) : std::nan(""); }
double LogHistogram::maxNs() const { return count_ ? static_cast<double>(max_ns_) : std::nan(""); }
double LogHistogram::meanNs() const { return count_ ? sum_ns_ / static_cast<double>(count_) : std::nan(""); }

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
  *s = Slot{true, false, seq, stamp_ns, published_ns, due_ns.has_value(), due_ns.value_or(0)};
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
  if (s->has_due && received_ns > s->due_ns) ++late_;
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
