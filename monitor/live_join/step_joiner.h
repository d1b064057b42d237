#pragma once
// Joins ground truth with the agents' states of the same stamp. Truth (swa/truth) and every agent's state
// (swa/uav<i>/state) arrive on different topics from different writers, so neither order nor completeness across
// them is guaranteed: a state can arrive before its truth sample, late, twice, or never.
//
// Rules (stamps are sim time; both streams are on 100 ms boundaries in a normal run):
//   - Truth must arrive with strictly increasing stamps; an older or equal stamp, or a sample naming a UAV id twice
//     (or a negative id), is dropped and counted.
//   - A step (one truth sample) is complete when every UAV whose agent the truth calls alive has a state with that
//     stamp; it is also released, incomplete, once `horizon` newer truth samples have arrived and `grace_s` of wall
//     time has passed since it arrived (advanceClock), or by flush() at the end. Missing states mean "no estimate
//     for that UAV at that step" (counted). The grace matters in lockstep, where `horizon` samples pass in a
//     fraction of a second: a state lost on the wire is repaired only after its writer's next heartbeat.
//   - Steps are released strictly in stamp order, each exactly once.
//   - A state is attached to the pending truth sample of its stamp (the first one per UAV wins, later ones are
//     duplicates), held while its truth sample may still come (stamp newer than every truth so far), and dropped
//     and counted when its UAV is not in that truth sample, its step was already released (late), or no truth
//     sample with its stamp ever arrives (unmatched).
// Memory: at most kMaxPending pending truth samples (the oldest is released when more arrive) and kMaxEarlyStates
// held states.

#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <vector>

#include "monitor_inputs.h"

namespace swa::monitor_node {

struct JoinCounters {
  std::uint64_t truth_samples = 0;         // accepted
  std::uint64_t truth_out_of_order = 0;    // stamp older than the newest truth sample: dropped
  std::uint64_t truth_duplicate = 0;       // stamp equal to the newest truth sample: dropped
  std::uint64_t truth_malformed = 0;       // a UAV id repeated or negative within the sample: dropped
  std::uint64_t truth_nonfinite_uavs = 0;  // UAV entries with a non-finite position or velocity (out of that step)
  std::uint64_t state_samples = 0;         // offered
  std::uint64_t state_unknown_uav = 0;     // UAV not in the truth sample of its stamp: dropped
  std::uint64_t state_duplicate = 0;       // a second state of one UAV for one stamp: dropped
  std::uint64_t state_late = 0;            // its step was already scored: dropped
  std::uint64_t state_unmatched = 0;       // no truth sample with its stamp: dropped
  std::uint64_t state_nonfinite = 0;       // non-finite estimate: joined, but no estimate (not a drop)
  std::uint64_t steps_incomplete = 0;      // steps released with a live agent's state missing
  std::uint64_t missing_states = 0;        // live agents without a state, summed over the released steps
};

struct JoinedStep {
  TruthSample truth;
  std::vector<std::optional<StateSample>> states;  // one per entry of truth.uavs, same order
};

class StepJoiner {
 public:
  static constexpr std::size_t kMaxEarlyStates = 4096;
  static constexpr std::size_t kMaxPending = 4096;

  // `horizon`: newer truth samples after which a step may be released incomplete (>= 1); `grace_s`: wall time after
  // its arrival before it may (>= 0).
  explicit StepJoiner(int horizon = 5, double grace_s = 0.0);

  // The wall clock (any monotonic seconds) that the grace is measured on; steps arriving from now on carry it.
  void advanceClock(double wall_s) { now_s_ = wall_s; }

  void addTruth(TruthSample truth);
  void addState(const StateSample& state);

  // Steps that are complete or past the horizon, in stamp order.
  std::vector<JoinedStep> takeReady();
  // Every pending step, complete or not, in stamp order; held states become unmatched. For the end of the run.
  std::vector<JoinedStep> flush();

  // No truth sample waiting for states.
  bool idle() const { return pending_.empty(); }
  std::optional<agent::StampNs> newestTruth() const { return newest_truth_; }
  const JoinCounters& counters() const { return counters_; }

 private:
  struct Pending {
    JoinedStep step;
    double arrived_s = 0.0;
    std::map<int, std::size_t> index;  // UAV id -> entry of step.truth.uavs
  };

  void attach(Pending& p, const StateSample& state);
  bool complete(const Pending& p) const;
  JoinedStep release();
  void dropEarlyBefore(agent::StampNs stamp);  // held states older than `stamp` can never match: unmatched
  bool wasReleased(agent::StampNs stamp) const;

  int horizon_;
  double grace_s_;
  double now_s_ = 0.0;
  std::deque<Pending> pending_;  // ascending stamps
  std::map<agent::StampNs, std::vector<StateSample>> early_;
  std::size_t early_count_ = 0;
  std::optional<agent::StampNs> newest_truth_;
  std::deque<agent::StampNs> released_;  // the most recent released stamps, ascending (late vs unmatched)
  JoinCounters counters_;
};

}  // namespace swa::monitor_node
