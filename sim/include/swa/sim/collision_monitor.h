#pragma once
// Counts collisions between UAVs. A collision is a pair entering contact (centres closer than 1.5 m); the UAVs are
// not pushed apart or removed, the count is a metric. Contact ends only once the pair is farther than 2.0 m apart:
// without this hysteresis two UAVs loitering at ~1.5 m would count a new "collision" on every gust.

#include <vector>

#include "swa/agent/geometry.h"

namespace swa::sim {

constexpr double kCollisionDistance_m = 1.5;
constexpr double kCollisionRelease_m = 2.0;

struct Contact {
  int uav = 0;
  int other_uav = 0;  // > uav
  double distance_m = 0.0;
};

class CollisionMonitor {
 public:
  explicit CollisionMonitor(int uav_count);

  // Pairs that came into contact since the previous call (in (uav, other_uav) order). O(N^2), fine for swarms of
  // tens to a few hundred UAVs at 100 Hz.
  std::vector<Contact> update(const std::vector<agent::Vec2>& positions_m);

  int onsets() const { return onsets_; }

 private:
  std::size_t pairIndex(std::size_t i, std::size_t j) const { return i * n_ + j; }

  std::size_t n_;
  std::vector<char> in_contact_;  // n x n, upper triangle used
  int onsets_ = 0;
};

}  // namespace swa::sim
