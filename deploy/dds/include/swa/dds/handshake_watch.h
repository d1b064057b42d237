#pragma once
// The participant's reconnection policy for a stalled DDS Security handshake. With security on, Fast DDS 2.9
// sometimes never completes the authentication handshake of a pair of participants that start together (measured:
// 8 agents + simulator, the simulator missed one agent for good in about 1 start in 4; deploy/README.md). A new
// participant (new GUID) gets a fresh handshake with everyone. So a node re-creates its participant when, with
// security on, it has not started yet (no input) and nothing it needs is matched: after 5 s, then 10, 20, 40, 60 s,
// so an absent peer costs one reconnection a minute at most and a running node is never disturbed.

#include <algorithm>
#include <chrono>

namespace swa::dds {

class HandshakeWatch {
 public:
  using Clock = std::chrono::steady_clock;

  explicit HandshakeWatch(bool secure) : secure_(secure) {}

  // A (new) participant was created at `now`.
  void connected(Clock::time_point now) { connected_at_ = now; }

  // Whether to re-create the participant now; if so, counts it (the next wait is twice as long).
  bool stalled(bool started, bool matched, Clock::time_point now) {
    if (!secure_ || started || matched) return false;
    const auto wait = std::min(kFirst * (1 << std::min(reconnects_, 4)), kMax);
    if (now - connected_at_ < wait) return false;
    ++reconnects_;
    return true;
  }

  int reconnects() const { return reconnects_; }

 private:
  static constexpr auto kFirst = std::chrono::seconds(5);
  static constexpr auto kMax = std::chrono::seconds(60);

  bool secure_;
  Clock::time_point connected_at_{};
  int reconnects_ = 0;
};

}  // namespace swa::dds
