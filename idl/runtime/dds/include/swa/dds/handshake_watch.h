#pragma once
// The participant's reconnection policy for a stalled DDS Security handshake. With security on, Fast DDS 2.9
// sometimes never completes the authentication handshake of a pair of participants that start together (measured:
// 8 agents + simulator, the simulator missed one agent for good in about 1 start in 4; deploy/README.md). A new
// participant (new GUID) gets a fresh handshake with everyone. So a node re-creates its participant when, with
// security on, it has not started yet (no input) and what it needs is not matched: after 5 s without progress, then
// 10, 20, 40, 60 s, so an absent peer costs one reconnection a minute at most and a running node is never disturbed.
//
// "Without progress": the wait counts from the participant's creation or from the last remote participant it
// authenticated, whichever is later (issue #46). Each handshake costs CPU on both sides, so a secured start of many
// participants on a small host takes longer than 5 s while every handshake still completes (18 participants through
// PX4 on 2 cores); re-creating then restarts the node's handshakes with everyone and, done by every node on the same
// schedule, fed a storm that never settled (bench_secure_launch.sh). A stalled pair shows as silence: every other
// handshake is done. Still, a node whose peers keep authenticating never waits beyond kPatience since its creation.

#include <algorithm>
#include <chrono>

namespace swa::dds {

class HandshakeWatch {
 public:
  using Clock = std::chrono::steady_clock;

  explicit HandshakeWatch(bool secure) : secure_(secure) {}

  // A (new) participant was created at `now`.
  void connected(Clock::time_point now) { connected_at_ = now; }

  // Whether to re-create the participant now; if so, counts it (the next wait is twice as long). `last_progress`: when
  // the participant last authenticated a remote one (Participant::lastAuthentication), the epoch if never.
  bool stalled(bool started, bool matched, Clock::time_point now, Clock::time_point last_progress = {}) {
    if (!secure_ || started || matched) return false;
    const auto wait = std::min(kFirst * (1 << std::min(reconnects_, 4)), kMax);
    const bool quiet = now - std::max(connected_at_, last_progress) >= wait;
    if (!quiet && now - connected_at_ < kPatience) return false;
    ++reconnects_;
    return true;
  }

  int reconnects() const { return reconnects_; }

 private:
  static constexpr auto kFirst = std::chrono::seconds(5);
  static constexpr auto kMax = std::chrono::seconds(60);
  static constexpr auto kPatience = std::chrono::seconds(60);

  bool secure_;
  Clock::time_point connected_at_{};
  int reconnects_ = 0;
};

}  // namespace swa::dds
