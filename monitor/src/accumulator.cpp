#include "swa/monitor/accumulator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace swa::monitor {
namespace {

using agent::StampNs;
using agent::Vec2;

StampNs toNs(double seconds) { return static_cast<StampNs>(std::llround(seconds * 1e9)); }
double toSeconds(StampNs ns) { return static_cast<double>(ns) * 1e-9; }

void checkStep(const StepInput& step) {
  if (!step.estimates.empty() && step.estimates.size() != step.uavs.size()) {
    throw std::invalid_argument("MetricsAccumulator: estimates must be empty or one per UAV");
  }
  std::vector<int> ids;
  ids.reserve(step.uavs.size());
  for (const UavTruth& u : step.uavs) ids.push_back(u.id);
  std::sort(ids.begin(), ids.end());
  if (std::adjacent_find(ids.begin(), ids.end()) != ids.end()) {
    throw std::invalid_argument("MetricsAccumulator: UAV ids repeat within a step");
  }
}

// NaN-ignoring minimum / maximum.
double nanMin(double a, double b) { return std::isnan(a) ? b : (std::isnan(b) ? a : std::min(a, b)); }
double nanMax(double a, double b) { return std::isnan(a) ? b : (std::isnan(b) ? a : std::max(a, b)); }

}  // namespace

MetricsAccumulator::MetricsAccumulator(const MetricsConfig& config)
    : config_((validate(config), config)),
      window_start_ns_(toNs(config.window_start_s)),
      final_window_ns_(toNs(config.final_window_s)),
      drift_window_ns_(toNs(config.drift_window_s)),
      drift_segment_ns_(toNs(config.drift_segment_s)) {
  if (!config.mission_legs.empty())
    mission_ = MissionScore(agent::MissionPlan(config.mission_legs), config.mission_start_s);
}

void MetricsAccumulator::replanMission(const std::vector<agent::MissionLeg>& legs, double start_s) {
  config_.mission_legs = legs;
  config_.mission_start_s = start_s;
  mission_.replan(agent::MissionPlan(legs), start_s);
}

const StepMetrics& MetricsAccumulator::add(const StepInput& step) {
  if (steps_ > 0 && step.stamp_ns < last_ns_) {
    throw std::invalid_argument("MetricsAccumulator: stamp " + std::to_string(step.stamp_ns) +
                                " ns is before the previous step (" + std::to_string(last_ns_) + " ns)");
  }
  checkStep(step);
  // Everything below is computed before any member changes, except what cannot throw.
  StepMetrics m;
  m.t_s = toSeconds(step.stamp_ns);
  m.geometry = computeGeometry(step.uavs, config_);
  m.nees = computeNees(step, config_.frame_velocity);

  if (steps_ == 0) first_ns_ = step.stamp_ns;
  last_ns_ = step.stamp_ns;
  ++steps_;

  m.new_collisions = updateCollisions(step);
  m.collisions = collisions_;
  m.drift_mps = updateDrift(step.stamp_ns, m.geometry);
  min_separation_m_ = nanMin(min_separation_m_, m.geometry.min_separation_m);

  final_samples_.push_back(
      {step.stamp_ns, m.geometry.mean_neighbor_distance_m, m.geometry.formation_error_m, m.geometry.edge_length_m});
  while (final_samples_.front().stamp_ns < step.stamp_ns - final_window_ns_) final_samples_.pop_front();

  last_positions_.clear();
  for (const UavTruth& u : step.uavs) {
    if (isPresent(u)) last_positions_[u.id] = u.position_m;
  }

  mission_.add(m.t_s, m.geometry, last_positions_);

  if (step.stamp_ns >= window_start_ns_) {
    if (!window_started_) {
      window_started_ = true;
      window_first_ns_ = step.stamp_ns;
      window_start_positions_ = last_positions_;
    }
    if (step.stamp_ns == window_first_ns_ || closeDriftSegment(step.stamp_ns)) {
      segment_first_ns_ = step.stamp_ns;
      segment_start_positions_ = last_positions_;
    }
    drift_max_mps_ = nanMax(drift_max_mps_, m.drift_mps);
    skipped_unknown_ += static_cast<std::uint64_t>(m.nees.skipped_unknown_id);
    skipped_invalid_ += static_cast<std::uint64_t>(m.nees.skipped_invalid);
    if (m.nees.evaluated > 0) {
      ++nees_steps_;
      nees_samples_ += static_cast<std::uint64_t>(m.nees.evaluated);
      nees_pos_sum_ += m.nees.position;
      nees_vel_sum_ += m.nees.velocity;
      const AneesBand& band = bandFor(m.nees.evaluated);
      if (m.nees.position >= band.low && m.nees.position <= band.high) ++pos_in_band_;
      if (m.nees.velocity >= band.low && m.nees.velocity <= band.high) ++vel_in_band_;
    }
  }
  last_ = m;
  return last_;
}

int MetricsAccumulator::updateCollisions(const StepInput& step) {
  std::vector<const UavTruth*> p;
  for (const UavTruth& u : step.uavs) {
    if (isPresent(u)) p.push_back(&u);
  }
  const double onset = config_.collision_distance_m;
  const double release = config_.collision_distance_m + config_.collision_release_m;
  std::set<std::pair<int, int>> next;  // pairs of absent UAVs are dropped by not being carried over
  int onsets = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const std::pair<int, int> key(std::min(p[i]->id, p[j]->id), std::max(p[i]->id, p[j]->id));
      const double d = (p[i]->position_m - p[j]->position_m).norm();
      if (contacts_.count(key) != 0) {
        if (d <= release) next.insert(key);
      } else if (d < onset) {
        next.insert(key);
        ++onsets;
      }
    }
  }
  contacts_.swap(next);
  collisions_ += static_cast<std::uint64_t>(onsets);
  return onsets;
}

namespace {

// Over the UAVs present at both ends: the length of their mean displacement (the centroid's, for a fixed set of
// UAVs) and the mean of their own displacements' lengths.
struct Displacement {
  double centroid_m = 0.0;
  double uav_m = 0.0;
  int common = 0;
};

Displacement meanDisplacement(const std::map<int, Vec2>& from, const std::map<int, Vec2>& to) {
  Displacement d;
  double sx = 0.0, sy = 0.0;  // plain doubles: GCC 12 mis-flags an Eigen accumulator here (-Wdangling-pointer)
  for (const auto& [id, start] : from) {
    const auto end = to.find(id);
    if (end == to.end()) continue;
    const Vec2 delta = end->second - start;
    sx += delta.x();
    sy += delta.y();
    d.uav_m += delta.norm();
    ++d.common;
  }
  if (d.common > 0) {
    d.centroid_m = std::hypot(sx, sy) / d.common;
    d.uav_m /= d.common;
  }
  return d;
}

}  // namespace

bool MetricsAccumulator::closeDriftSegment(StampNs stamp) {
  if (stamp - segment_first_ns_ < drift_segment_ns_) return false;
  const Displacement d = meanDisplacement(segment_start_positions_, last_positions_);
  if (d.common > 0) {
    segment_speed_sum_ += d.centroid_m / toSeconds(stamp - segment_first_ns_);
    ++segments_;
  }
  return true;
}

double MetricsAccumulator::updateDrift(StampNs stamp, const Geometry& geometry) {
  if (!agent::isFinite(geometry.centroid_m)) return kNaN;
  centroid_history_.emplace_back(stamp, geometry.centroid_m);
  const StampNs back = stamp - drift_window_ns_;
  // Keep exactly one sample at or before `back`: the latest such one.
  while (centroid_history_.size() >= 2 && centroid_history_[1].first <= back) centroid_history_.pop_front();
  const auto& [then_ns, then_c] = centroid_history_.front();
  if (then_ns > back) return kNaN;
  return (geometry.centroid_m - then_c).norm() / toSeconds(stamp - then_ns);
}

double MetricsAccumulator::finalMean(double FinalSample::*field) const {
  double sum = 0.0;
  int n = 0;
  for (const FinalSample& f : final_samples_) {
    if (!std::isfinite(f.*field)) continue;
    sum += f.*field;
    ++n;
  }
  return n > 0 ? sum / n : kNaN;
}

const AneesBand& MetricsAccumulator::bandFor(int k) {
  while (static_cast<int>(bands_.size()) < k) {
    bands_.push_back(aneesBand(static_cast<int>(bands_.size()) + 1, 2, config_.anees_alpha));
  }
  return bands_[static_cast<std::size_t>(k - 1)];
}

Summary MetricsAccumulator::summary() const {
  Summary s;
  s.steps = steps_;
  if (steps_ == 0) return s;
  s.duration_s = toSeconds(last_ns_ - first_ns_);
  s.uav_count = last_.geometry.uav_count;
  s.groups = last_.geometry.groups;
  s.spread_m = last_.geometry.spread_m;
  s.min_separation_m = min_separation_m_;
  s.collisions = collisions_;

  s.mean_neighbor_distance_m = finalMean(&FinalSample::d_nb);
  s.formation_error_m = finalMean(&FinalSample::formation_error);
  s.edge_length_m = finalMean(&FinalSample::edge_length);
  if (mission_.active()) {
    const MissionFigures f = mission_.figures(last_.geometry, last_positions_);
    s.mission_end_error_m = f.end_error_m;
    s.mission_path_error_m = f.path_error_m;
    s.mission_d_nb_moving_m = f.d_nb_moving_m;
    s.mission_uav_end_error_m = f.uav_end_error_m;
    s.mission_uav_end_spread_m = f.uav_end_spread_m;
  }

  if (!window_started_) return s;
  s.window_start_s = toSeconds(window_first_ns_);
  s.window_duration_s = toSeconds(last_ns_ - window_first_ns_);
  s.drift_speed_max_mps = drift_max_mps_;

  const Displacement window = meanDisplacement(window_start_positions_, last_positions_);
  if (window.common > 0) {
    s.centroid_displacement_m = window.centroid_m;
    s.uav_displacement_m = window.uav_m;
    if (s.window_duration_s > 0.0) s.drift_velocity_mps = s.centroid_displacement_m / s.window_duration_s;
  }
  if (segments_ > 0) s.drift_velocity_windows_mps = segment_speed_sum_ / segments_;

  s.nees_steps = nees_steps_;
  s.nees_samples = nees_samples_;
  s.nees_skipped_unknown_id = skipped_unknown_;
  s.nees_skipped_invalid = skipped_invalid_;
  if (nees_steps_ > 0) {
    s.anees_position = nees_pos_sum_ / nees_steps_;
    s.anees_velocity = nees_vel_sum_ / nees_steps_;
    s.anees_agents = std::max(1, static_cast<int>(std::llround(static_cast<double>(nees_samples_) / nees_steps_)));
    const AneesBand band = aneesBand(s.anees_agents, 2, config_.anees_alpha);
    s.anees_band_low = band.low;
    s.anees_band_high = band.high;
    s.anees_position_in_band = static_cast<double>(pos_in_band_) / nees_steps_;
    s.anees_velocity_in_band = static_cast<double>(vel_in_band_) / nees_steps_;
  }
  return s;
}

}  // namespace swa::monitor
