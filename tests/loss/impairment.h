#pragma once
// What the loss emulator (swa_netem.cpp) does to each packet, without the kernel: drop it with probability `loss`, or
// hold it for a delay drawn uniformly from [delay - jitter, delay + jitter] and release it then. Seeded: the same
// seed gives the same decisions for the same packet sequence. Released packets may overtake each other (jitter), as
// on a real network. Pure: the caller passes the time.

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <queue>
#include <random>
#include <stdexcept>
#include <vector>

namespace swa::netem {

using Clock = std::chrono::steady_clock;

struct ImpairmentConfig {
  double loss = 0.0;                    // [0, 1)
  std::chrono::microseconds delay{0};   // mean added one-way delay
  std::chrono::microseconds jitter{0};  // half-width of the uniform spread, <= delay
  std::uint64_t seed = 1;
};

// Decisions for packets in arrival order.
class Impairment {
 public:
  explicit Impairment(const ImpairmentConfig& c)
      : c_(c), rng_(c.seed), spread_(-static_cast<double>(c.jitter.count()), static_cast<double>(c.jitter.count())) {
    if (!(c.loss >= 0.0 && c.loss < 1.0)) throw std::invalid_argument("loss must be in [0, 1)");
    if (c.delay.count() < 0 || c.jitter.count() < 0 || c.jitter > c.delay) {
      throw std::invalid_argument("need 0 <= jitter <= delay");
    }
  }

  // nullopt: drop. Otherwise the delay to hold the packet for.
  std::optional<std::chrono::microseconds> decide() {
    if (unit_(rng_) < c_.loss) return std::nullopt;
    if (c_.jitter.count() == 0) return c_.delay;
    return c_.delay + std::chrono::microseconds(static_cast<std::int64_t>(spread_(rng_)));
  }

 private:
  ImpairmentConfig c_;
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
  std::uniform_real_distribution<double> spread_;
};

// Packets held until their release time, earliest first.
class ReleaseQueue {
 public:
  struct Held {
    Clock::time_point release;
    std::uint32_t id;  // the kernel's packet id
    bool operator>(const Held& o) const { return release > o.release; }
  };

  void hold(Clock::time_point release, std::uint32_t id) { heap_.push({release, id}); }
  // Calls `release(id)` for every packet due at `now`, earliest first.
  template <class F>
  std::size_t releaseDue(Clock::time_point now, F&& release) {
    std::size_t n = 0;
    while (!heap_.empty() && heap_.top().release <= now) {
      release(heap_.top().id);
      heap_.pop();
      ++n;
    }
    return n;
  }
  std::optional<Clock::time_point> next() const {
    if (heap_.empty()) return std::nullopt;
    return heap_.top().release;
  }
  std::size_t size() const { return heap_.size(); }

 private:
  std::priority_queue<Held, std::vector<Held>, std::greater<Held>> heap_;
};

}  // namespace swa::netem
