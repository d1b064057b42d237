#include "step_joiner.h"

#include <algorithm>
#include <set>
#include <stdexcept>
#include <utility>

namespace swa::monitor_node {
namespace {

// Released stamps remembered to tell a late state from one whose stamp never had a truth sample: 100 s at 10 Hz,
// far beyond the 10 s of history a state writer keeps.
constexpr std::size_t kReleasedMemory = 1000;

}  // namespace

StepJoiner::StepJoiner(int horizon, double grace_s) : horizon_(horizon), grace_s_(grace_s) {
  if (horizon < 1) throw std::invalid_argument("StepJoiner: horizon must be >= 1");
  if (!(grace_s >= 0.0)) throw std::invalid_argument("StepJoiner: grace must be >= 0 s");
}

void StepJoiner::addTruth(TruthSample truth) {
  std::set<int> ids;
  for (const monitor::UavTruth& u : truth.uavs) {
    if (u.id < 0 || !ids.insert(u.id).second) {
      ++counters_.truth_malformed;
      return;
    }
  }
  if (truth.agent_alive.size() != truth.uavs.size()) {
    ++counters_.truth_malformed;
    return;
  }
  if (newest_truth_ && truth.stamp_ns <= *newest_truth_) {
    ++(truth.stamp_ns == *newest_truth_ ? counters_.truth_duplicate : counters_.truth_out_of_order);
    return;
  }
  ++counters_.truth_samples;
  for (const monitor::UavTruth& u : truth.uavs) {
    if (!agent::isFinite(u.position_m) || !agent::isFinite(u.velocity_mps)) ++counters_.truth_nonfinite_uavs;
  }
  newest_truth_ = truth.stamp_ns;
  dropEarlyBefore(truth.stamp_ns);

  Pending p;
  p.arrived_s = now_s_;
  p.step.states.resize(truth.uavs.size());
  for (std::size_t k = 0; k < truth.uavs.size(); ++k) p.index[truth.uavs[k].id] = k;
  p.step.truth = std::move(truth);
  if (const auto held = early_.find(p.step.truth.stamp_ns); held != early_.end()) {
    for (const StateSample& s : held->second) attach(p, s);
    early_count_ -= held->second.size();
    early_.erase(held);
  }
  pending_.push_back(std::move(p));
}

void StepJoiner::addState(const StateSample& state) {
  ++counters_.state_samples;
  if (!state.finite) ++counters_.state_nonfinite;
  if (!newest_truth_ || state.stamp_ns > *newest_truth_) {
    // Its truth sample may still come: hold it, the oldest giving way when too many are held.
    early_[state.stamp_ns].push_back(state);
    if (++early_count_ > kMaxEarlyStates) {
      auto oldest = early_.begin();
      counters_.state_unmatched += oldest->second.size();
      early_count_ -= oldest->second.size();
      early_.erase(oldest);
    }
    return;
  }
  const auto it = std::find_if(pending_.begin(), pending_.end(),
                               [&](const Pending& p) { return p.step.truth.stamp_ns == state.stamp_ns; });
  if (it != pending_.end()) {
    attach(*it, state);
  } else if (wasReleased(state.stamp_ns)) {
    ++counters_.state_late;
  } else {
    ++counters_.state_unmatched;
  }
}

void StepJoiner::attach(Pending& p, const StateSample& state) {
  const auto k = p.index.find(state.uav);
  if (k == p.index.end()) {
    ++counters_.state_unknown_uav;
  } else if (p.step.states[k->second]) {
    ++counters_.state_duplicate;
  } else {
    p.step.states[k->second] = state;
  }
}

bool StepJoiner::complete(const Pending& p) const {
  for (std::size_t k = 0; k < p.step.states.size(); ++k) {
    if (p.step.truth.agent_alive[k] && !p.step.states[k]) return false;
  }
  return true;
}

std::vector<JoinedStep> StepJoiner::takeReady() {
  std::vector<JoinedStep> out;
  const auto overdue = [this](const Pending& p) {
    return pending_.size() - 1 >= static_cast<std::size_t>(horizon_) && now_s_ - p.arrived_s >= grace_s_;
  };
  while (!pending_.empty() &&
         (complete(pending_.front()) || overdue(pending_.front()) || pending_.size() > kMaxPending)) {
    out.push_back(release());
  }
  return out;
}

std::vector<JoinedStep> StepJoiner::flush() {
  std::vector<JoinedStep> out;
  while (!pending_.empty()) out.push_back(release());
  for (const auto& [stamp, states] : early_) counters_.state_unmatched += states.size();
  early_.clear();
  early_count_ = 0;
  return out;
}

JoinedStep StepJoiner::release() {
  Pending p = std::move(pending_.front());
  pending_.pop_front();
  std::uint64_t missing = 0;
  for (std::size_t k = 0; k < p.step.states.size(); ++k) {
    if (p.step.truth.agent_alive[k] && !p.step.states[k]) ++missing;
  }
  counters_.missing_states += missing;
  if (missing > 0) ++counters_.steps_incomplete;
  released_.push_back(p.step.truth.stamp_ns);
  if (released_.size() > kReleasedMemory) released_.pop_front();
  return std::move(p.step);
}

void StepJoiner::dropEarlyBefore(agent::StampNs stamp) {
  while (!early_.empty() && early_.begin()->first < stamp) {
    counters_.state_unmatched += early_.begin()->second.size();
    early_count_ -= early_.begin()->second.size();
    early_.erase(early_.begin());
  }
}

bool StepJoiner::wasReleased(agent::StampNs stamp) const {
  return std::binary_search(released_.begin(), released_.end(), stamp);
}

}  // namespace swa::monitor_node
