#include "swa/monitor/mission_score.h"

#include <cmath>

namespace swa::monitor {

using agent::Vec2;

ReplannedMission replanMission(const std::vector<agent::MissionLeg>& legs, double start_s, double at_s,
                               const agent::MissionCommand& command) {
  ReplannedMission r;
  if (legs.empty() || at_s < start_s) {
    r.start_s = at_s;
  } else {
    r.legs = agent::flownUntil(agent::MissionPlan(legs), at_s - start_s);
    r.start_s = start_s;
  }
  agent::appendCommand(r.legs, command);
  return r;
}

MissionScore::MissionScore(const agent::MissionPlan& plan, double start_s) : plan_(plan), start_s_(start_s) {}

void MissionScore::replan(const agent::MissionPlan& plan, double start_s) {
  plan_ = plan;
  if (started_ && start_s != start_s_) {  // a new mission: what was scored of the old one does not belong to it
    started_ = false;
    path_error_sum_ = d_nb_sum_ = 0.0;
    moving_steps_ = d_nb_steps_ = 0;
  }
  start_s_ = start_s;
}

void MissionScore::add(double t_s, const Geometry& geometry, const std::map<int, Vec2>& positions) {
  if (!active() || !(t_s >= start_s_) || !agent::isFinite(geometry.centroid_m)) return;
  if (!started_) {
    started_ = true;
    start_centroid_ = geometry.centroid_m;
    start_positions_ = positions;
  }
  const double t = t_s - start_s_;
  if (t > plan_.duration_s()) return;
  path_error_sum_ += (geometry.centroid_m - (start_centroid_ + plan_.pathAt(t))).norm();
  ++moving_steps_;
  if (std::isfinite(geometry.mean_neighbor_distance_m)) {
    d_nb_sum_ += geometry.mean_neighbor_distance_m;
    ++d_nb_steps_;
  }
}

MissionFigures MissionScore::figures(const Geometry& last, const std::map<int, Vec2>& positions) const {
  MissionFigures f;
  if (!started_) return f;
  const Vec2 end = plan_.endPoint();
  if (agent::isFinite(last.centroid_m)) f.end_error_m = (last.centroid_m - (start_centroid_ + end)).norm();
  if (moving_steps_ > 0) f.path_error_m = path_error_sum_ / moving_steps_;
  if (d_nb_steps_ > 0) f.d_nb_moving_m = d_nb_sum_ / d_nb_steps_;
  // The UAVs present at both ends.
  Vec2 mean_end = Vec2::Zero();
  double error_sum = 0.0;
  int n = 0;
  for (const auto& [id, start] : start_positions_) {
    const auto at = positions.find(id);
    if (at == positions.end()) continue;
    error_sum += (at->second - (start + end)).norm();
    mean_end += at->second;
    ++n;
  }
  if (n == 0) return f;
  f.uav_end_error_m = error_sum / n;
  mean_end /= n;
  double spread2 = 0.0;
  for (const auto& [id, start] : start_positions_) {
    const auto at = positions.find(id);
    if (at != positions.end()) spread2 += (at->second - mean_end).squaredNorm();
  }
  f.uav_end_spread_m = std::sqrt(spread2 / n);
  return f;
}

}  // namespace swa::monitor
