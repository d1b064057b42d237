#pragma once
// A latency histogram for the programs that time their loops (swa_sim's loop latency, swa_px4_bridge's hop): pure,
// fixed size, no allocation after construction, so it can sit on a hot path for runs of any length.

#include <cstdint>
#include <limits>
#include <vector>

namespace swa::app {

using WallNs = std::int64_t;  // nanoseconds on a monotonic wall clock

// Counts of non-negative values (nanoseconds) in log-spaced bins: kBinsPerDecade bins per factor of 10 from kLowNs
// (1 us) to kHighNs (100 s); values below / above go to an underflow / overflow bin. Count, sum, min and max are
// exact. quantile() returns the geometric centre of the bin holding the requested rank, clamped to [min, max]: it
// is within relativeResolution() of the true order statistic for values inside the range, and exact for the
// smallest and largest value. Fixed size (~6.5 KB), no allocation in add().
class LogHistogram {
 public:
  static constexpr int kBinsPerDecade = 100;
  static constexpr int kDecades = 8;
  static constexpr double kLowNs = 1e3;    // 1 us
  static constexpr double kHighNs = 1e11;  // 100 s
  // Half the width of a bin relative to its geometric centre: 10^(1 / (2 * kBinsPerDecade)) - 1, i.e. 1.16 %.
  static double relativeResolution();

  LogHistogram();
  void add(WallNs value_ns);
  void merge(const LogHistogram& other);

  std::uint64_t count() const { return count_; }
  // q in [0, 1]: the value of rank ceil(q * count) (rank 1 for q = 0). NaN when empty.
  double quantileNs(double q) const;
  double minNs() const;   // NaN when empty
  double maxNs() const;   // NaN when empty
  double meanNs() const;  // NaN when empty

 private:
  static constexpr int kBins = kBinsPerDecade * kDecades;
  double binCentreNs(int bin) const;

  std::vector<std::uint64_t> bins_;  // [0] underflow, [1 .. kBins] in range, [kBins + 1] overflow
  std::uint64_t count_ = 0;
  double sum_ns_ = 0.0;
  WallNs min_ns_ = std::numeric_limits<WallNs>::max();
  WallNs max_ns_ = std::numeric_limits<WallNs>::min();
};

}  // namespace swa::app
