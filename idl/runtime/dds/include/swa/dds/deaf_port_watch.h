#pragma once
// When a process no longer hears one of its own shared-memory ports (shm_ports.h), polled from its main loop. Every
// SWA process has one: a peer can re-create a port under any of them, and one that keeps listening on the deleted
// segment loses everything sent to it while discovery stays matched (seen for the simulator after a stop; an agent or
// a bridge deaf before its first sample would not even show in its silence watch).
// The caller re-creates its participant when a port is named, then calls reset().

#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace swa::dds {

class DeafPortWatch {
 public:
  using Clock = std::chrono::steady_clock;
  // Which ports this process listens on (ownSharedMemoryPorts), and which of those are deaf (deafSharedMemoryPorts);
  // a test passes its own.
  struct Lookups {
    std::function<std::vector<int>()> own;
    std::function<std::vector<int>(const std::vector<int>&)> deaf_among;
  };
  // A look costs about 0.05 ms once the ports are known (0.2 ms to find them, once per participant): four a second
  // cost nothing, and a deaf port is found well within a lockstep simulator's 2 s agent timeout.
  static constexpr auto kPeriod = std::chrono::milliseconds(250);

  explicit DeafPortWatch(Lookups lookups, Clock::duration period = kPeriod);
  DeafPortWatch();  // this process

  // A port found deaf that was not named since the last reset(), looking at most once a period.
  std::optional<int> poll(Clock::time_point now);
  // The participant was re-created: its ports are found again, and a port of the same number found deaf later is a
  // new deafness.
  void reset();

 private:
  Lookups lookups_;
  Clock::duration period_;
  std::optional<Clock::time_point> next_look_;
  std::optional<std::vector<int>> own_;  // found at the first look after a reset
  std::vector<int> named_;
};

// What `who` says when it connects: "<who>: listening on shared-memory ports 7413 7414" (the tests find its ports
// there); nothing when it has none (shared memory off).
void sayOwnSharedMemoryPorts(const std::string& who);

// Why a process re-creates its participant, for its log: the port, what happened to it, and that what `senders` send
// to it is lost.
std::string deafPortReason(int port, const std::string& senders);

}  // namespace swa::dds
