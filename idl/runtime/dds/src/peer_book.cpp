#include "swa/dds/peer_book.h"

#include <charconv>
#include <tuple>
#include <utility>
#include <vector>

namespace swa::dds {
namespace {

constexpr const char* kMagic = "swa-peer/1";
constexpr std::size_t kMaxCardBytes = 255;  // USER_DATA is sent in every participant announcement

// Card values must not contain the separators; anything else is kept.
std::string clean(const std::string& s, std::size_t max) {
  std::string out;
  for (const char c : s) {
    if (out.size() == max) break;
    out += (c == ';' || c == '=' || static_cast<unsigned char>(c) < 0x20) ? '_' : c;
  }
  return out;
}

template <class T>
bool parseInt(const std::string& s, T& out) {
  const char* end = s.data() + s.size();
  const auto r = std::from_chars(s.data(), end, out);
  return r.ec == std::errc() && r.ptr == end && !s.empty();
}

}  // namespace

std::string encodePeerCard(const PeerCard& card) {
  std::string text = std::string(kMagic) + ";started_ns=" + std::to_string(card.started_ns) +
                     ";pid=" + std::to_string(card.pid) + ";swarm=" + clean(card.swarm, 160) + ";host=";
  text += clean(card.host, text.size() < kMaxCardBytes ? kMaxCardBytes - text.size() : 0);
  return text;
}

std::optional<PeerCard> decodePeerCard(const std::string& text) {
  if (text.size() > kMaxCardBytes || text.rfind(kMagic, 0) != 0) return std::nullopt;
  PeerCard card;
  bool started = false, pid = false, swarm = false, host = false;
  std::size_t pos = std::string(kMagic).size();
  while (pos < text.size()) {
    if (text[pos] != ';') return std::nullopt;
    const std::size_t eq = text.find('=', pos + 1);
    if (eq == std::string::npos) return std::nullopt;
    std::size_t next = text.find(';', eq + 1);
    if (next == std::string::npos) next = text.size();
    const std::string key = text.substr(pos + 1, eq - pos - 1);
    const std::string value = text.substr(eq + 1, next - eq - 1);
    if (key == "started_ns") {
      started = parseInt(value, card.started_ns);
      if (!started) return std::nullopt;
    } else if (key == "pid") {
      pid = parseInt(value, card.pid);
      if (!pid) return std::nullopt;
    } else if (key == "swarm") {
      card.swarm = value;
      swarm = true;
    } else if (key == "host") {
      card.host = value;
      host = true;
    }  // unknown keys: a later version's, ignored
    pos = next;
  }
  if (!started || !pid || !swarm || !host) return std::nullopt;
  return card;
}

bool olderThan(const PeerCard& a, const PeerKey& a_key, const PeerCard& b, const PeerKey& b_key) {
  return std::tie(a.started_ns, a_key) < std::tie(b.started_ns, b_key);
}

PeerBook::PeerBook(std::string self_name, PeerCard self_card, PeerKey self_key)
    : self_name_(std::move(self_name)), self_card_(std::move(self_card)), self_key_(self_key) {}

void PeerBook::discovered(const Peer& peer) {
  if (peer.key == self_key_) return;
  if (const auto it = expired_.find(peer.key); it != expired_.end()) {
    ++returned_;
    last_returned_ = it->second;
    last_returned_key_ = peer.key;
    expired_.erase(it);
  }
  // A changed QoS announces a live peer again: not a new twin.
  const bool fresh = live_.count(peer.key) == 0;
  if (fresh && isTwin(peer) && olderThan(self_card_, self_key_, *peer.card, peer.key)) {
    if (younger_twins_.size() >= kMaxExpired) younger_twins_.pop_front();
    younger_twins_.push_back(peer);
  }
  live_[peer.key] = peer;
}

void PeerBook::lost(const PeerKey& key, bool lease_expired) {
  const auto it = live_.find(key);
  if (it == live_.end()) return;
  // A peer of another swarm never matches our endpoints, so its return cannot have cost us any (with two swarms on
  // a starved host, every return of the other swarm's participants made a whole swarm reconnect). A peer without a
  // card (another vendor's bridge) may be ours.
  const bool ours = !it->second.card || it->second.card->swarm == self_card_.swarm;
  if (lease_expired && ours) {
    if (expired_.size() >= kMaxExpired) expired_.erase(expired_.begin());
    expired_[key] = it->second.name;
  }
  if (gone_.size() >= kMaxExpired) gone_.pop_front();
  gone_.push_back(key);
  live_.erase(it);
}

std::vector<PeerKey> PeerBook::takeGone() {
  std::vector<PeerKey> gone(gone_.begin(), gone_.end());
  gone_.clear();
  return gone;
}

std::optional<Peer> PeerBook::oldestTwin() const {
  std::optional<Peer> oldest;
  for (const auto& [key, peer] : live_) {
    if (!isTwin(peer)) continue;
    if (!oldest || olderThan(*peer.card, key, *oldest->card, oldest->key)) oldest = peer;
  }
  return oldest;
}

std::vector<Peer> PeerBook::takeYoungerTwins() {
  std::vector<Peer> twins(younger_twins_.begin(), younger_twins_.end());
  younger_twins_.clear();
  return twins;
}

bool PeerBook::isTwin(const Peer& peer) const {
  return peer.name == self_name_ && peer.card && peer.card->swarm == self_card_.swarm;
}

bool PeerBook::mustGiveWay() const {
  const std::optional<Peer> twin = oldestTwin();
  return twin && olderThan(*twin->card, twin->key, self_card_, self_key_);
}

}  // namespace swa::dds
