#pragma once
// Loop-latency bookkeeping of swa_sim: for every sensor sample the simulator publishes to a UAV (its IMU sample, the
// one a command answers), the wall time from publication to the reception of the command that answers it, whether
// that command missed the step it answers (realtime: came after the UAV's next IMU sample was due and the simulator
// had taken that step), and which samples were never answered. Pure: no DDS, no clock (times are nanoseconds on any
// monotonic clock, passed in), and no allocation after construction, so it can sit on the simulator's hot path for
// runs of any length.

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "swa/app/log_histogram.h"

namespace swa::sim_node {

using app::LogHistogram;
using app::WallNs;

// What one run's commands looked like (see CommandLatencyTracker).
struct LatencyReport {
  std::uint64_t published = 0;   // samples judged: answered + missing (the last samples, still in time, excluded)
  std::uint64_t answered = 0;    // samples answered (first answer counted; latency of each in the histogram)
  std::uint64_t late = 0;        // answered after their deadline
  std::uint64_t missing = 0;     // never answered although their deadline passed (or evicted unanswered)
  std::uint64_t duplicates = 0;  // further answers to an already answered sample
  std::uint64_t unmatched = 0;   // answers naming no sample in the window (older than the window, or foreign)
  double p50_us = 0.0, p99_us = 0.0, max_us = 0.0, mean_us = 0.0;  // NaN when nothing was answered
  double lateFraction() const;                                     // late / published, 0 when nothing was judged
  double missingFraction() const;                                  // missing / published, 0 when nothing was judged
};

// Per UAV, a ring of the last `window` samples published (slot = seq mod window). published() records a sample
// with its publication time and deadline; answered() matches an answer by (seq, stamp) and records its latency;
// finish() closes the books. A sample is MISSING when it is evicted from the ring unanswered, or is unanswered at
// finish() with its deadline passed (samples without a deadline count as missing at finish() if unanswered). An
// answer is LATE when it missed the step it answers: received after its sample's deadline once stepTaken() has
// closed that step. Samples with no deadline are never late (lockstep).
class CommandLatencyTracker {
 public:
  CommandLatencyTracker(int uav_count, int window = 512);

  void published(int uav, std::uint32_t seq, std::int64_t stamp_ns, WallNs published_ns, std::optional<WallNs> due_ns);
  void answered(int uav, std::uint32_t seq, std::int64_t stamp_ns, WallNs received_ns);
  // The simulator took the next step (applied the commands it had) at `taken_ns`. Until then an answer to each UAV's
  // newest sample is in time even past its deadline, because it is still applied (a simulator that is itself late
  // must not blame the agents); from then on the deadline is max(deadline, taken_ns).
  void stepTaken(WallNs taken_ns);
  // Whether every UAV's newest sample has been answered (or it has none).
  bool newestAnswered() const;
  // Unanswered samples whose deadline is at or before `now_ns` (or that have none) become missing; those still in
  // time are dropped from the judgement. Idempotent; published()/answered() after it are undefined.
  void finish(WallNs now_ns);

  LatencyReport report() const;
  const LogHistogram& histogram() const { return histogram_; }

 private:
  struct Slot {
    bool used = false;
    bool answered = false;
    std::uint32_t seq = 0;
    std::int64_t stamp_ns = 0;
    WallNs published_ns = 0;
    bool has_due = false;
    WallNs due_ns = 0;
    bool step_taken = false;  // the step this sample's answer feeds has been taken (stepTaken)
  };
  Slot* slot(int uav, std::uint32_t seq);

  int uav_count_;
  int window_;
  std::vector<Slot> slots_;                           // uav_count * window
  std::vector<std::optional<std::uint32_t>> newest_;  // per UAV: the seq of its newest sample
  LogHistogram histogram_;
  std::uint64_t late_ = 0, missing_ = 0, duplicates_ = 0, unmatched_ = 0;
};

}  // namespace swa::sim_node
