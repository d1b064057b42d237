#pragma once
// Drops the history a re-created participant is sent again. The sensor writers are TRANSIENT_LOCAL (profiles.xml): a
// reader that matches gets up to a reader history's worth of old samples first. When the node re-creates its
// participant (agent_node.h) its new readers get the samples it already processed once more, seconds old; the core
// would reject them one by one, and after a few consistent ones take them for a producer restart and restart its
// estimates on the old timeline (measured: 7 resynchronisations and 2 s without commands).
//
// Rule, per stream: after arm(), samples not newer than the newest one passed before are dropped, at most `budget` of
// them (the reader history depth: a genuine producer restart, whose stamps never get newer, is let through after
// that); the first newer sample ends the replay of that stream.
// Pure: no clock, no DDS; the node owns one instance.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "sample_order.h"

namespace swa::agent_node {

class ReplayFilter {
 public:
  // Whether the sample goes on to the agent; remembers the newest stamp passed.
  bool pass(Stream stream, agent::StampNs stamp_ns) {
    Lane& l = lanes_[static_cast<std::size_t>(stream)];
    if (l.budget > 0 && l.newest && stamp_ns <= *l.newest) {
      --l.budget;
      ++dropped_;
      return false;
    }
    l.budget = 0;
    if (!l.newest || stamp_ns > *l.newest) l.newest = stamp_ns;
    return true;
  }

  // A new participant: the next samples of `stream` may be its history again, at most `budget` of them.
  void arm(Stream stream, std::size_t budget) { lanes_[static_cast<std::size_t>(stream)].budget = budget; }

  std::uint64_t dropped() const { return dropped_; }

 private:
  struct Lane {
    std::optional<agent::StampNs> newest;
    std::size_t budget = 0;
  };
  std::array<Lane, 3> lanes_{};
  std::uint64_t dropped_ = 0;
};

}  // namespace swa::agent_node
