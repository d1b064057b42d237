#include "swa/monitor/swarm_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/Cholesky>

namespace swa::monitor {
namespace {

using agent::Mat2;
using agent::Vec2;

// Central-difference half step of kFitDerivative, in metres of relative displacement: far above the fit's 1e-9 m
// Gauss-Newton tolerance (velocity error ~1e-7 of the relative speed), far below any formation scale.
constexpr double kStencilM = 1e-2;

const UavTruth* findPresent(const std::vector<UavTruth>& uavs, int id) {
  for (const UavTruth& u : uavs) {
    if (u.id == id && isPresent(u)) return &u;
  }
  return nullptr;
}

struct FrameNeighbour {
  double distance;
  int id;
  Vec2 relative_position;  // p_j - p_i
  Vec2 relative_velocity;  // v_j - v_i
};

}  // namespace

EstimateRecord estimateFromDiagnostics(const agent::Diagnostics& d, const agent::FormationConfig& formation) {
  EstimateRecord r;
  r.valid = d.mode != agent::Mode::kStandalone && d.stage == agent::Stage::kTracking && d.frame_valid &&
            d.neighbour_count > 0;
  r.position_m = d.position_m;
  r.position_cov_m2 = d.position_cov_m2;
  r.velocity_mps = d.velocity_mps;
  r.velocity_cov_m2ps2 = d.velocity_cov_m2ps2;
  r.neighbour_count = d.neighbour_count;
  r.neighbour_ids = d.neighbour_ids;
  r.formation = formation;
  return r;
}

void validate(const MetricsConfig& c) {
  std::string errors;
  auto check = [&errors](bool ok, const char* what) {
    if (!ok) errors += std::string(errors.empty() ? "" : "; ") + what;
  };
  check(std::isfinite(c.formation.radius_m) && c.formation.radius_m > 0.0, "formation.radius_m must be > 0");
  check(std::isfinite(c.radius_tolerance) && c.radius_tolerance > 0.0, "radius_tolerance must be > 0");
  check(std::isfinite(c.collision_distance_m) && c.collision_distance_m > 0.0, "collision_distance_m must be > 0");
  check(std::isfinite(c.drift_segment_s) && c.drift_segment_s > 0.0, "drift_segment_s must be > 0");
  check(std::isfinite(c.collision_release_m) && c.collision_release_m >= 0.0, "collision_release_m must be >= 0");
  check(std::isfinite(c.group_link_factor) && c.group_link_factor > 0.0, "group_link_factor must be > 0");
  check(c.distance_neighbours >= 1, "distance_neighbours must be >= 1");
  check(std::isfinite(c.window_start_s) && std::fabs(c.window_start_s) < 9e9, "window_start_s must be finite");
  check(std::isfinite(c.final_window_s) && c.final_window_s >= 0.0 && c.final_window_s < 9e9,
        "final_window_s must be >= 0");
  check(std::isfinite(c.drift_window_s) && c.drift_window_s > 0.0 && c.drift_window_s < 9e9,
        "drift_window_s must be > 0");
  check(c.anees_alpha > 0.0 && c.anees_alpha < 1.0, "anees_alpha must lie in (0, 1)");
  check(c.frame_velocity == FrameVelocity::kNeighbourMean || c.frame_velocity == FrameVelocity::kFitDerivative,
        "frame_velocity unknown");
  check(std::isfinite(c.mission_start_s) && std::fabs(c.mission_start_s) < 9e9, "mission_start_s must be finite");
  agent::MissionConfig mission;
  mission.legs = c.mission_legs;
  mission.max_speed_mps = std::numeric_limits<double>::max();  // the speed limit is the agents' configuration's
  const auto why = agent::missionProblem(mission);
  check(!why, why ? why->c_str() : "");
  if (!errors.empty()) throw std::invalid_argument("MetricsConfig: " + errors);
}

int countGroups(const std::vector<Vec2>& positions, double link_distance_m) {
  const std::size_t n = positions.size();
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  auto root = [&parent](std::size_t i) {
    while (parent[i] != i) {
      parent[i] = parent[parent[i]];  // path halving
      i = parent[i];
    }
    return i;
  };
  int groups = static_cast<int>(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      if ((positions[i] - positions[j]).norm() >= link_distance_m) continue;
      const std::size_t a = root(i);
      const std::size_t b = root(j);
      if (a == b) continue;
      parent[std::max(a, b)] = std::min(a, b);
      --groups;
    }
  }
  return groups;
}

Geometry computeGeometry(const std::vector<UavTruth>& uavs, const MetricsConfig& config) {
  std::vector<Vec2> p;
  p.reserve(uavs.size());
  for (const UavTruth& u : uavs) {
    if (isPresent(u)) p.push_back(u.position_m);
  }
  Geometry g;
  const std::size_t n = p.size();
  g.uav_count = static_cast<int>(n);
  if (n == 0) return g;

  Vec2 sum = Vec2::Zero();
  for (const Vec2& x : p) sum += x;
  g.centroid_m = sum / static_cast<double>(n);
  g.spread_m = 0.0;
  for (const Vec2& x : p) g.spread_m = std::max(g.spread_m, (x - g.centroid_m).norm());
  g.groups = countGroups(p, config.group_link_factor * config.formation.radius_m);
  if (n < 2) return g;

  std::vector<double> dist(n * n, 0.0);
  double min_sep = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const double d = (p[i] - p[j]).norm();
      dist[i * n + j] = d;
      dist[j * n + i] = d;
      min_sep = std::min(min_sep, d);
    }
  }
  g.min_separation_m = min_sep;

  const std::size_t m = std::min(static_cast<std::size_t>(config.distance_neighbours), n - 1);
  const double r = config.formation.radius_m;
  std::vector<double> others(n - 1);
  double d_nb_sum = 0.0;
  double fe_sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t k = 0;
    for (std::size_t j = 0; j < n; ++j) {
      if (j != i) others[k++] = dist[i * n + j];
    }
    std::partial_sort(others.begin(), others.begin() + static_cast<std::ptrdiff_t>(m), others.end());
    double d_sum = 0.0;
    double e_sum = 0.0;
    for (std::size_t j = 0; j < m; ++j) {
      d_sum += others[j];
      e_sum += std::fabs(others[j] - r);
    }
    d_nb_sum += d_sum / static_cast<double>(m);
    fe_sum += e_sum / static_cast<double>(m);
  }
  g.mean_neighbor_distance_m = d_nb_sum / static_cast<double>(n);
  g.formation_error_m = fe_sum / static_cast<double>(n);
  g.edge_length_m = meanGabrielEdgeLength(p);
  return g;
}

double meanGabrielEdgeLength(const std::vector<Vec2>& p) {
  double sum = 0.0;
  int edges = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      bool blocked = false;
      for (std::size_t m = 0; m < p.size() && !blocked; ++m) {
        blocked = m != i && m != j && agent::inDiametralDisc(p[i], p[j], p[m]);
      }
      if (blocked) continue;
      sum += (p[i] - p[j]).norm();
      ++edges;
    }
  }
  return edges > 0 ? sum / edges : kNaN;
}

TruthInFrame truthInFloatingFrame(const UavTruth& self, const std::vector<UavTruth>& uavs, const EstimateRecord& record,
                                  FrameVelocity method) {
  TruthInFrame out;
  if (!isPresent(self)) {
    out.status = TruthStatus::kSelfAbsent;
    return out;
  }
  if (record.neighbour_count <= 0 || record.neighbour_count > agent::kMaxNeighbours) {
    out.status = TruthStatus::kNoNeighbours;
    return out;
  }
  std::vector<FrameNeighbour> nb;
  nb.reserve(static_cast<std::size_t>(record.neighbour_count));
  for (int k = 0; k < record.neighbour_count; ++k) {
    const int id = record.neighbour_ids[static_cast<std::size_t>(k)];
    const UavTruth* u = id == self.id ? nullptr : findPresent(uavs, id);
    if (u == nullptr) {
      out.status = TruthStatus::kUnknownNeighbour;
      return out;
    }
    const Vec2 q = u->position_m - self.position_m;
    nb.push_back({q.norm(), id, q, u->velocity_mps - self.velocity_mps});
  }
  // In the record's order, not re-sorted by true distance: with the weighted fit, the two the agent ranks nearest
  // weigh 1, and that is part of the frame it reports. Ranked by the true distances, the truth would jump between
  // two frames whenever near-equal distances swap, an error no estimate of the agent's frame can see.

  auto fitAt = [&nb, &record](double step_m, double speed) {
    const double dt = speed > 0.0 ? step_m / speed : 0.0;  // seconds of relative motion
    agent::NeighbourPositions positions;
    for (const FrameNeighbour& f : nb) {
      positions.position[static_cast<std::size_t>(positions.count++)] = f.relative_position + dt * f.relative_velocity;
    }
    return agent::fitFloatingFrame(positions, record.formation.radius_m, record.formation.circle_fit,
                                   record.formation.far_neighbour_weight);
  };

  const agent::FrameFit fit = fitAt(0.0, 0.0);
  out.fit_case = fit.fit_case;
  if (!fit.valid || !agent::isFinite(fit.centre)) {
    out.status = TruthStatus::kFitFailed;
    return out;
  }
  out.status = TruthStatus::kOk;
  out.position_m = -fit.centre;

  Vec2 mean_relative_velocity = Vec2::Zero();
  double speed = 0.0;  // largest relative speed |v_j - v_i|
  for (const FrameNeighbour& f : nb) {
    mean_relative_velocity += f.relative_velocity;
    speed = std::max(speed, f.relative_velocity.norm());
  }
  mean_relative_velocity /= static_cast<double>(nb.size());
  // v_i - mean_j v_j = -mean_j (v_j - v_i)
  out.velocity_mps = -mean_relative_velocity;
  if (method != FrameVelocity::kFitDerivative || speed == 0.0) return out;

  // r_c(q + s t w) with w = (v_j - v_i) / s: d r_c / dt = s * (r_c(+h) - r_c(-h)) / (2 h), h in metres.
  const agent::FrameFit plus = fitAt(kStencilM, speed);
  const agent::FrameFit minus = fitAt(-kStencilM, speed);
  if (plus.valid && minus.valid && plus.fit_case == fit.fit_case && minus.fit_case == fit.fit_case) {
    const Vec2 derivative = speed * (plus.centre - minus.centre) / (2.0 * kStencilM);
    if (agent::isFinite(derivative)) {
      out.velocity_mps = -derivative;
      return out;
    }
  }
  out.velocity_fallback = true;
  return out;
}

double nees(const Vec2& error, const Mat2& covariance) {
  if (!agent::isFinite(error) || !agent::isCovariance(covariance)) return kNaN;
  const Vec2 solved = covariance.ldlt().solve(error);
  return error.dot(solved);
}

NeesStep computeNees(const StepInput& step, FrameVelocity method) {
  NeesStep out;
  if (step.estimates.empty()) return out;
  if (step.estimates.size() != step.uavs.size()) {
    throw std::invalid_argument("computeNees: estimates must be empty or one per UAV");
  }
  double pos_sum = 0.0;
  double vel_sum = 0.0;
  for (std::size_t i = 0; i < step.uavs.size(); ++i) {
    const UavTruth& self = step.uavs[i];
    const EstimateRecord& rec = step.estimates[i];
    if (!rec.valid) {
      if (isPresent(self)) ++out.no_estimate;
      continue;
    }
    const TruthInFrame truth = truthInFloatingFrame(self, step.uavs, rec, method);
    if (truth.status == TruthStatus::kUnknownNeighbour) {
      ++out.skipped_unknown_id;
      continue;
    }
    if (!truth.ok()) {
      ++out.skipped_invalid;
      continue;
    }
    const double ep = nees(rec.position_m - truth.position_m, rec.position_cov_m2);
    const double ev = nees(rec.velocity_mps - truth.velocity_mps, rec.velocity_cov_m2ps2);
    if (!std::isfinite(ep) || !std::isfinite(ev)) {
      ++out.skipped_invalid;
      continue;
    }
    pos_sum += ep;
    vel_sum += ev;
    ++out.evaluated;
  }
  if (out.evaluated > 0) {
    out.position = pos_sum / out.evaluated;
    out.velocity = vel_sum / out.evaluated;
  }
  return out;
}

}  // namespace swa::monitor
