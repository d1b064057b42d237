#pragma once
// One commander per UAV. DDS lets any participant in the swarm write swa/uav<i>/cmd_vel: a second agent started with
// the same id, a test tool, a rogue. The simulator and the autopilot bridges apply the commands of one writer per UAV,
// the owner: the first writer heard from, until it has been silent for `handover` (its agent crashed and a restarted
// one took over) or until its participant left (an agent that re-created its participant: its new writer takes over
// at once); commands of any other writer meanwhile are refused and counted, and each new refused writer is reported
// once.
// A refused command is not always a rogue's: an agent that re-created its participant answers with its new writer
// before the old participant's goodbye has been processed. In lockstep that answer is the only one the step will get,
// so the caller keeps the newest refused command per UAV and, once every newer command has been admitted, asks
// `heldCommand` what to do with it: apply it if its writer would be admitted now, drop it once it is twice the
// handover time old, else keep it.
// Pure (no DDS, no clock): the node passes the writer's identity (its GUID) and the time the sample arrived.

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <set>
#include <vector>

namespace swa::dds {

using WriterId = std::array<std::uint8_t, 16>;

enum class Admission {
  kOwner,     // from the owner: apply it as usual
  kHandover,  // a new owner (the first writer, or the old owner was silent): apply it
  kRefused,   // another writer while the owner is active: drop it
};

enum class Held { kKeep, kRelease, kDrop };  // a refused command kept by the caller (see above)

class CommandGate {
 public:
  using Clock = std::chrono::steady_clock;

  CommandGate(int uav_count, Clock::duration handover);

  Admission admit(int uav, const WriterId& writer, Clock::time_point received);
  // Whether a command of `writer` arriving at `at` would be applied (kOwner or kHandover); changes nothing.
  bool admits(int uav, const WriterId& writer, Clock::time_point at) const;
  // A command of `writer` refused when it arrived at `received`, judged at `now` (see above).
  Held heldCommand(int uav, const WriterId& writer, Clock::time_point received, Clock::time_point now) const;
  // A refused writer not reported before (the caller logs it): true once per (UAV, writer).
  bool firstRefusal(int uav, const WriterId& writer);
  // Moves every owner's last-heard time by `lost` (a stall of the simulator itself: nobody could be heard), but not
  // past `now` (a sample drained after the stall, before it was noticed, is already recent).
  void shift(Clock::duration lost, Clock::time_point now);
  // The participant with this GUID prefix left (a goodbye, or its lease expired): its writers own nothing any more.
  // If it comes back with the same writer before another one spoke, that writer is the owner again.
  void participantGone(const std::array<std::uint8_t, 12>& prefix);

  std::uint64_t refused() const { return refused_; }
  std::uint64_t handovers() const { return handovers_; }  // owner changes after the first owner of each UAV
  std::size_t refusedWriters() const { return reported_.size(); }

 private:
  struct Owner {
    WriterId writer{};
    Clock::time_point last_heard{};
    bool gone = false;  // its participant left
  };
  Clock::duration handover_;
  std::vector<std::optional<Owner>> owners_;
  std::set<std::pair<int, WriterId>> reported_;  // bounded by the writers that ever tried, at most a few per UAV
  std::uint64_t refused_ = 0;
  std::uint64_t handovers_ = 0;
};

}  // namespace swa::dds
