#include "swa/app/log_histogram.h"

#include <algorithm>
#include <cmath>

namespace swa::app {

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
    if (b == 0) return minNs();          // below the range: the best we know is the smallest value
    if (b == kBins + 1) return maxNs();  // above the range
    return std::clamp(binCentreNs(b), minNs(), maxNs());
  }
  return maxNs();
}

double LogHistogram::minNs() const { return count_ ? static_cast<double>(min_ns_) : std::nan(""); }
double LogHistogram::maxNs() const { return count_ ? static_cast<double>(max_ns_) : std::nan(""); }
double LogHistogram::meanNs() const { return count_ ? sum_ns_ / static_cast<double>(count_) : std::nan(""); }

}  // namespace swa::app
