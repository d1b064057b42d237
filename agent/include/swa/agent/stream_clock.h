#pragma once
// The stamps of one input stream, judged against the stream's own recent stamps: the agent has no clock of its own,
// so "the future" and "a restart" can only be told from what the stream did before.
//
//   accept    the stamp is after the last accepted one by at most max_jump;
//   reject    it is not after it (out of order, a duplicate) or further ahead than max_jump (a future stamp);
//   resync    unless it is the resync_samples-th consecutive rejected sample of one consistent new timeline: each
//             after the previous by the stream's own period within a factor of 2 (the period is a running mean of
//             accepted steps; before it is known, by at most max_jump). A producer restarted its clock (an autopilot
//             reboot), or the old timeline was the wrong one (a single bogus stamp that got accepted). The stream
//             then continues from it, and the caller restarts whatever it built on the old timeline.
// Duplicates and random stamps practically never re-synchronise (a flood of stale stamps spread over 5 s hits the
// period band of a 100 Hz stream about once in 300 samples, and needs resync_samples - 1 hits in a row); a writer
// that keeps a consistent false timeline at the right rate can (DDS Security is what keeps such writers out).

#include <cstdint>

#include "swa/agent/samples.h"

namespace swa::agent {

class StreamClock {
 public:
  enum class Verdict { kAccept, kResync, kOutOfOrder, kFuture };

  StreamClock(StampNs max_jump_ns, int resync_samples);

  // Judges the next sample's stamp and, when accepted (kAccept, kResync), makes it the stream's last stamp.
  Verdict check(StampNs stamp_ns);
  // The stream goes on from `stamp_ns`, further ahead than max_jump, when another clock vouches for the stamp: a
  // stream that fell silent for a while (ArduPilot sends no GNSS while its receiver is unhealthy) and came back on
  // the IMU's timeline. The period is kept: the silence was no step of the stream.
  void resume(StampNs stamp_ns);

  bool started() const { return started_; }
  StampNs last() const { return last_ns_; }
  std::uint64_t resyncs() const { return resyncs_; }

 private:
  bool follows(StampNs previous, StampNs next) const;   // next in (previous, previous + max_jump]
  bool atPeriod(StampNs previous, StampNs next) const;  // next - previous within a factor 2 of the period

  StampNs max_jump_ns_;
  int resync_samples_;
  bool started_ = false;
  StampNs last_ns_ = 0;
  double period_ns_ = 0.0;   // running mean of accepted steps; 0 = not known yet
  int candidate_count_ = 0;  // consecutive rejected samples of one consistent timeline
  StampNs candidate_last_ns_ = 0;
  std::uint64_t resyncs_ = 0;
};

}  // namespace swa::agent
