#pragma once
// Notices a channel that broke while discovery still calls it matched. Seen in CI after the simulator had been
// stopped (SIGSTOP) for 4.75 s, beyond the DDS lease: one agent never got a sample again while the simulator's writers
// stayed matched, and its UAV stayed on failsafe. What the agent sees: no sample while their writer is matched and it
// is itself running. The cure is the one for endpoints lost after an expired lease (agent_node.cpp): re-create the
// participant.
//
// The class is written for any channel whose health shows in polls: "fine" (a sample arrived recently), "owed" (the
// agent had samples and is running) and "peers" (matched writers). It counts from the last fine poll, but only while
// something is owed and a peer is matched (a paused producer, or one forgotten by discovery, owes nothing; the count
// starts over when it is owed again). Not fine for `limit`: reconnect, and the count starts over. The limit is longer
// than the DDS lease (4 s, profiles.xml): a peer that died or was stopped is forgotten by discovery first.
//
// Not used for the agent's own commands: "every command acknowledged" was tried (a chaos run lost two agents' commands
// after a 1.75 s stop) but a fast lockstep run (1 ms steps, 5 ms acknowledgment delay) is almost never fully
// acknowledged, so healthy agents would reconnect.
// Pure: the caller supplies the time and the channel's state; the node owns the instance.

#include <algorithm>
#include <chrono>
#include <optional>

namespace swa::agent_node {

class LinkWatch {
 public:
  using Clock = std::chrono::steady_clock;

  explicit LinkWatch(Clock::duration limit) : limit_(limit) {}

  // One poll. `fine`: the channel is fine now; `owed`: something is owed (the agent had samples and runs); `peers`:
  // matched peers. Returns how long the channel was not fine when that reaches the limit (the count then
  // starts over), otherwise nothing.
  std::optional<Clock::duration> poll(Clock::time_point now, bool fine, bool owed, int peers) {
    if (fine || !owed || peers < 1 || !since_) {
      since_ = now;
      return std::nullopt;
    }
    const Clock::duration broken = now - *since_;
    longest_ = std::max(longest_, broken);
    if (broken < limit_) return std::nullopt;
    since_ = now;
    return broken;
  }

  // A new participant: nothing is owed yet.
  void restart() { since_.reset(); }

  // The longest time the channel was not fine so far (diagnostics: a healthy one stays far below the limit).
  Clock::duration longest() const { return longest_; }

 private:
  Clock::duration limit_;
  std::optional<Clock::time_point> since_;
  Clock::duration longest_{};
};

}  // namespace swa::agent_node
