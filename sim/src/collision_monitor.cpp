#include "swa/sim/collision_monitor.h"

namespace swa::sim {

CollisionMonitor::CollisionMonitor(int uav_count)
    : n_(uav_count > 0 ? static_cast<std::size_t>(uav_count) : 0), in_contact_(n_ * n_, 0) {}

std::vector<Contact> CollisionMonitor::update(const std::vector<agent::Vec2>& positions_m) {
  std::vector<Contact> onsets;
  for (std::size_t i = 0; i < n_; ++i) {
    for (std::size_t j = i + 1; j < n_; ++j) {
      const double distance = (positions_m[i] - positions_m[j]).norm();
      char& contact = in_contact_[pairIndex(i, j)];
      if (!contact && distance < kCollisionDistance_m) {
        contact = 1;
        ++onsets_;
        onsets.push_back({static_cast<int>(i), static_cast<int>(j), distance});
      } else if (contact && distance > kCollisionRelease_m) {
        contact = 0;
      }
    }
  }
  return onsets;
}

}  // namespace swa::sim
