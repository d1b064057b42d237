#pragma once
// Who else is on the domain, as DDS participant discovery reports it, for two decisions no single sample can make:
//
//   - A twin: a live participant with the same name in the same swarm (two `swa_agent --id 3`, two simulators). Both
//     would write the same topics and a UAV would get two streams of commands. Every SWA participant announces a card
//     (swarm, start time, pid, host) in its USER_DATA; of two twins the older (earlier start, then the smaller GUID
//     prefix: both sides decide alike) keeps running and the younger refuses to.
//   - A peer back after its lease expired: a participant that went silent longer than the lease (SIGSTOP, a starved
//     host) and announced itself again. It never dropped us, and Fast DDS 2.9 then sometimes does not re-send all of
//     its endpoints to us (measured: an agent's cmd_vel writer never re-matched the simulator's reader in about 1 stop
//     of 5 s in 3), so the node that sees it re-creates its own participant: a new one is discovered afresh by all.
//
// No DDS include: the participant's listener feeds it (peer_listener.cpp), tests drive it directly. Not thread-safe:
// the owner serialises calls.

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace swa::dds {

// What a SWA participant announces about itself (USER_DATA). `swarm` empty: the default partition.
struct PeerCard {
  std::string swarm;
  std::int64_t started_ns = 0;  // wall clock (system_clock) at start: comparable across hosts to clock sync
  long pid = 0;
  std::string host;
};

// "swa-peer/1;swarm=..;started_ns=..;pid=..;host=.." (at most 255 bytes: host and swarm are cut to fit).
std::string encodePeerCard(const PeerCard& card);
// nullopt for anything that is not a card of this format (another vendor's USER_DATA, garbage).
std::optional<PeerCard> decodePeerCard(const std::string& text);

using PeerKey = std::array<std::uint8_t, 12>;  // the participant's GUID prefix

struct Peer {
  PeerKey key{};
  std::string name;
  std::optional<PeerCard> card;
};

// True if `a` is older than `b` (started earlier; equal starts: the smaller key).
bool olderThan(const PeerCard& a, const PeerKey& a_key, const PeerCard& b, const PeerKey& b_key);

class PeerBook {
 public:
  PeerBook(std::string self_name, PeerCard self_card, PeerKey self_key = {});
  void setSelfKey(const PeerKey& key) { self_key_ = key; }

  void discovered(const Peer& peer);
  // `lease_expired`: dropped for silence (not a clean goodbye).
  void lost(const PeerKey& key, bool lease_expired);

  // Live peers with our name in our swarm: the oldest of them, if any.
  std::optional<Peer> oldestTwin() const;
  // Whether some twin is older than us (we must give way).
  bool mustGiveWay() const;
  // Twins younger than us discovered since the last call, in order (bounded like the expired ones). Kept apart from
  // the live peers because a younger twin gives way at once: on a loaded host it is often discovered and gone again
  // between two polls of the node, which must still report that one tried to run.
  std::vector<Peer> takeYoungerTwins();
  // Peers of our swarm (or without a card) that announced themselves again after their lease had expired, since
  // construction.
  int returnedAfterLease() const { return returned_; }
  const std::string& lastReturned() const { return last_returned_; }
  const PeerKey& lastReturnedKey() const { return last_returned_key_; }
  // Peers that left (goodbye or lease) since the last call, oldest first (bounded like the expired ones): a node
  // that gives one writer the say over a UAV frees the say of a writer whose participant left (command_gate.h).
  std::vector<PeerKey> takeGone();
  // Peers remembered as expired (bounded: crashed peers never come back).
  std::size_t expiredRemembered() const { return expired_.size(); }
  static constexpr std::size_t kMaxExpired = 1024;

 private:
  bool isTwin(const Peer& peer) const;  // our name, our swarm

  std::string self_name_;
  PeerCard self_card_;
  PeerKey self_key_;
  std::map<PeerKey, Peer> live_;
  std::map<PeerKey, std::string> expired_;  // dropped for silence, by name, until they come back
  int returned_ = 0;
  std::string last_returned_;
  PeerKey last_returned_key_{};
  std::deque<PeerKey> gone_;
  std::deque<Peer> younger_twins_;
};

}  // namespace swa::dds
