#include "lockstep_tracker.h"

#include <stdexcept>

namespace swa::sim_node {

LockstepTracker::LockstepTracker(int uav_count)
    : alive_(static_cast<std::size_t>(uav_count), true),
      answered_(static_cast<std::size_t>(uav_count), false),
      ever_answered_(static_cast<std::size_t>(uav_count), false),
      current_(static_cast<std::size_t>(uav_count)),
      previous_(static_cast<std::size_t>(uav_count)),
      dead_since_(static_cast<std::size_t>(uav_count)),
      caught_up_to_(static_cast<std::size_t>(uav_count)),
      catching_up_(static_cast<std::size_t>(uav_count), false) {}

void LockstepTracker::begin(const std::vector<std::optional<agent::StampNs>>& imu_stamps) {
  if (imu_stamps.size() != alive_.size()) throw std::invalid_argument("LockstepTracker::begin: wrong UAV count");
  for (std::size_t i = 0; i < alive_.size(); ++i) {
    if (current_[i]) previous_[i] = current_[i];
    current_[i] = imu_stamps[i];
    answered_[i] = false;
  }
}

Verdict LockstepTracker::onAnswer(int uav, agent::StampNs answered_stamp_ns) {
  const auto i = static_cast<std::size_t>(uav);
  if (uav < 0 || i >= alive_.size()) return Verdict::kIgnore;
  const bool answers_current = current_[i] && *current_[i] == answered_stamp_ns;
  if (alive_[i]) {
    if (!answers_current || answered_[i]) return Verdict::kIgnore;
    answered_[i] = true;
    ever_answered_[i] = true;
    return Verdict::kApply;
  }
  const bool answers_previous = previous_[i] && *previous_[i] == answered_stamp_ns;
  if (!answers_current && !answers_previous) {
    // An answer to a sample sent since it was declared dead: the agent runs again, behind the steps. Without a wait
    // it may never catch up (with no live agent the steps follow each other as fast as the simulator can go).
    const bool since_death = dead_since_[i] && answered_stamp_ns >= *dead_since_[i];
    const bool progress = !caught_up_to_[i] || answered_stamp_ns > *caught_up_to_[i];
    if (since_death && progress) {
      catching_up_[i] = true;
      caught_up_to_[i] = answered_stamp_ns;
    }
    return Verdict::kIgnore;
  }
  alive_[i] = true;
  catching_up_[i] = false;
  answered_[i] = answers_current;
  ever_answered_[i] = true;
  return Verdict::kRejoin;
}

bool LockstepTracker::complete() const {
  for (std::size_t i = 0; i < alive_.size(); ++i) {
    if (waitedFor(i)) return false;
  }
  return true;
}

std::vector<int> LockstepTracker::waitingFor() const {
  std::vector<int> out;
  for (std::size_t i = 0; i < alive_.size(); ++i) {
    if (waitedFor(i)) out.push_back(static_cast<int>(i));
  }
  return out;
}

bool LockstepTracker::waitingForNewcomer() const {
  for (int i : waitingFor()) {
    if (!ever_answered_[static_cast<std::size_t>(i)]) return true;
  }
  return false;
}

std::vector<int> LockstepTracker::expire() {
  std::vector<int> dead;
  for (std::size_t i = 0; i < alive_.size(); ++i) {
    if (!waitedFor(i)) continue;
    if (alive_[i]) {
      alive_[i] = false;
      dead_since_[i] = current_[i];
      caught_up_to_[i].reset();
      dead.push_back(static_cast<int>(i));
    }
    catching_up_[i] = false;  // still dead; waited for again only once it answers further on
  }
  return dead;
}

int LockstepTracker::aliveCount() const {
  int n = 0;
  for (bool a : alive_) n += a ? 1 : 0;
  return n;
}

}  // namespace swa::sim_node
