#pragma once
// Notices a channel that broke while discovery still calls it matched. Seen in CI, both ways, after the simulator
// had been stopped (SIGSTOP):
//  - chaos test, 1.75 s stop: two agents received and answered every IMU sample, but the simulator got none of their
//    commands (nor their acknowledgments) again, so their UAVs stayed on failsafe to the end of the run. What the
//    agent sees: its reliable command writer is never fully acknowledged while it writes.
//  - a 4.75 s stop (beyond the lease): one agent never got a sample again while the simulator's writers stayed
//    matched. What the agent sees: no sample while their writer is matched and it is itself running.
// The node watches each way with one instance; the cure is the one for endpoints lost after an expired lease
// (agent_node.cpp): re-create the participant.
//
// Rule, written for commands (for samples read "a sample arrived", "had samples and runs", "writers"): commands
// count as unheard from the last poll that found the writer fully acknowledged, but only while the agent is writing
// them and a reader is matched (a paused producer sends nothing to answer, so nothing is owed; the count starts over
// when sending resumes). Unheard for `limit`: reconnect, and the count starts over. The limit is longer than the DDS
// lease (4 s, profiles.xml): a matched peer that died or was stopped (a killed recorder, a stopped simulator) is
// forgotten by discovery before it can trigger a reconnection.
// Pure: the caller supplies the time and the channel's state; the node owns the instances.

#include <algorithm>
#include <chrono>
#include <optional>

namespace swa::agent_node {

class LinkWatch {
 public:
  using Clock = std::chrono::steady_clock;

  explicit LinkWatch(Clock::duration limit) : limit_(limit) {}

  // One poll. `acknowledged`: every sample written so far is acknowledged by every matched reader; `sending`: a
  // command was written recently; `readers`: matched readers of the commands. Returns how long the commands went
  // unheard when that reaches the limit (the count then starts over), otherwise nothing.
  std::optional<Clock::duration> poll(Clock::time_point now, bool acknowledged, bool sending, int readers) {
    if (acknowledged || !sending || readers < 1 || !since_) {
      since_ = now;
      return std::nullopt;
    }
    const Clock::duration unheard = now - *since_;
    longest_ = std::max(longest_, unheard);
    if (unheard < limit_) return std::nullopt;
    since_ = now;
    return unheard;
  }

  // A new writer: nothing is owed yet.
  void restart() { since_.reset(); }

  // The longest time commands went unheard so far (diagnostics: a healthy link stays far below the limit).
  Clock::duration longest() const { return longest_; }

 private:
  Clock::duration limit_;
  std::optional<Clock::time_point> since_;
  Clock::duration longest_{};
};

}  // namespace swa::agent_node
