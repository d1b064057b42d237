#pragma once
// Notices IMU samples that stopped while their writer stays matched. Seen in CI after the simulator had been stopped
// (SIGSTOP) for 4.75 s, beyond the DDS lease: Fast DDS 2.9 had re-created the agent's shared-memory port under it
// (deploy/README.md), one agent never got a sample again while the simulator's writers stayed matched, and its UAV
// stayed on failsafe. The cure is the one for endpoints lost after an expired lease (agent_node.cpp): re-create the
// participant.
//
// It counts from the last poll with samples arriving, but only while samples are expected (the agent had some and
// runs itself) and a writer is matched: a paused writer, or one forgotten by discovery, owes nothing, and the count
// starts over when samples are expected again. Silent for `limit`: report, and the count starts over. The limit is
// longer than the DDS lease (4 s, profiles.xml), so a writer that died or was stopped is forgotten by discovery first.
//
// The other direction (the agent's commands not reaching the simulator) is not watched here: a command writer that
// is not fully acknowledged is no sign of it, since a fast lockstep run (1 ms steps, 5 ms acknowledgment delay) almost
// never is. The agent re-creates its participant instead when the reader of its commands comes back after its lease
// (agent_node.cpp). Pure: the caller supplies the time and the channel's state; the node owns the instance.

#include <chrono>
#include <optional>

namespace swa::agent_node {

class SilenceWatch {
 public:
  using Clock = std::chrono::steady_clock;

  explicit SilenceWatch(Clock::duration limit) : limit_(limit) {}

  // One poll. `arriving`: a sample came recently; `expected`: samples are owed (the agent had some and runs);
  // `writers`: matched writers of them. Returns how long they were silent when that reaches the limit (the count then
  // starts over), otherwise nothing.
  std::optional<Clock::duration> poll(Clock::time_point now, bool arriving, bool expected, int writers) {
    if (arriving || !expected || writers < 1 || !counting_) {
      counting_ = true;
      since_ = now;
      return std::nullopt;
    }
    const Clock::duration silent = now - since_;
    if (silent < limit_) return std::nullopt;
    since_ = now;
    return silent;
  }

  // A new participant: nothing is owed yet.
  void restart() { counting_ = false; }

 private:
  Clock::duration limit_;
  bool counting_ = false;  // since_ is set
  Clock::time_point since_{};
};

}  // namespace swa::agent_node
