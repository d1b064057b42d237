#include "swa/agent/mission.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace swa::agent {
namespace {

constexpr double kSamePointM = 1e-6;

}  // namespace

bool appendLegTo(std::vector<MissionLeg>& legs, const Vec2& to_m, double speed_mps) {
  if (!isFinite(to_m) || !std::isfinite(speed_mps) || speed_mps <= 0.0) return false;
  Vec2 from = Vec2::Zero();
  for (const MissionLeg& l : legs) from += l.velocity_mps * l.duration_s;
  const Vec2 way = to_m - from;
  const double distance = way.norm();
  // The end of the legs so far carries their round-off (0.6 m/s x 5 s ends 4e-16 m off 3 m): a point within a
  // micrometre of it is that point, not a leg of 1e-16 s.
  if (distance <= kSamePointM) return true;
  legs.push_back({way * (speed_mps / distance), distance / speed_mps});
  return true;
}

std::optional<std::string> missionProblem(const MissionConfig& config) {
  std::ostringstream why;
  if (!std::isfinite(config.start_s) || config.start_s < 0.0) {
    why << "mission.start_s = " << config.start_s << " must be finite and >= 0";
    return why.str();
  }
  if (!std::isfinite(config.max_speed_mps) || config.max_speed_mps <= 0.0) {
    why << "mission.max_speed_mps = " << config.max_speed_mps << " must be finite and > 0";
    return why.str();
  }
  if (config.legs.size() > kMaxMissionLegs) {
    why << "mission.legs has " << config.legs.size() << " legs; at most " << kMaxMissionLegs;
    return why.str();
  }
  for (std::size_t i = 0; i < config.legs.size(); ++i) {
    const MissionLeg& l = config.legs[i];
    const double speed = l.velocity_mps.norm();
    if (!isFinite(l.velocity_mps) || !std::isfinite(l.duration_s)) {
      why << "mission.legs[" << i << "] is not finite";
    } else if (l.duration_s <= 0.0) {
      why << "mission.legs[" << i << "].duration_s = " << l.duration_s << " must be > 0";
    } else if (speed > config.max_speed_mps) {
      why << "mission.legs[" << i << "] flies at " << speed
          << " m/s, above mission.max_speed_mps = " << config.max_speed_mps << " m/s";
    } else {
      continue;
    }
    return why.str();
  }
  return std::nullopt;
}

MissionPlan::MissionPlan(std::vector<MissionLeg> legs) : legs_(std::move(legs)) {
  starts_s_.reserve(legs_.size() + 1);
  points_.reserve(legs_.size() + 1);
  starts_s_.push_back(0.0);
  points_.push_back(Vec2::Zero());
  for (const MissionLeg& l : legs_) {
    starts_s_.push_back(starts_s_.back() + l.duration_s);
    points_.push_back(points_.back() + l.velocity_mps * l.duration_s);
  }
}

std::optional<std::string> missionCommandProblem(const MissionCommand& command, double max_speed_mps,
                                                 double max_abs_position_m) {
  std::ostringstream why;
  if (command.hold != command.legs.empty()) {
    return command.hold ? "a hold with legs" : "no legs and no hold";
  }
  if (command.legs.size() > kMaxMissionLegs) {
    why << command.legs.size() << " legs; at most " << kMaxMissionLegs;
    return why.str();
  }
  for (std::size_t i = 0; i < command.legs.size(); ++i) {
    const MissionCommandLeg& l = command.legs[i];
    const bool to = l.kind == MissionCommandLeg::Kind::kTo;
    const double time_or_speed = to ? l.speed_mps : l.duration_s;
    const double speed = to ? l.speed_mps : l.value.norm();
    if (!isFinite(l.value) || !std::isfinite(time_or_speed)) {
      why << "leg " << i << " is not finite";
    } else if (time_or_speed <= 0.0) {
      why << "leg " << i << (to ? " speed_mps = " : " duration_s = ") << time_or_speed << " must be > 0";
    } else if (speed > max_speed_mps) {
      why << "leg " << i << " flies at " << speed << " m/s, above mission.max_speed_mps = " << max_speed_mps;
    } else if (to && l.value.norm() > max_abs_position_m) {
      why << "leg " << i << " goes to a point " << l.value.norm() << " m from the mission's start, beyond "
          << "limits.max_abs_position_m = " << max_abs_position_m;
    } else {
      continue;
    }
    return why.str();
  }
  return std::nullopt;
}

std::vector<MissionLeg> flownUntil(const MissionPlan& plan, double at_s) {
  std::vector<MissionLeg> flown;
  if (!(at_s > 0.0)) return flown;
  double t = 0.0;
  for (const MissionLeg& l : plan.legs()) {
    if (t + l.duration_s >= at_s) {
      flown.push_back({l.velocity_mps, at_s - t});
      return flown;
    }
    flown.push_back(l);
    t += l.duration_s;
  }
  flown.push_back({Vec2::Zero(), at_s - t});
  return flown;
}

void appendCommand(std::vector<MissionLeg>& legs, const MissionCommand& command) {
  for (const MissionCommandLeg& l : command.legs) {
    if (l.kind == MissionCommandLeg::Kind::kTo) {
      appendLegTo(legs, l.value, l.speed_mps);
    } else {
      legs.push_back({l.value, l.duration_s});
    }
  }
}

int MissionPlan::legAt(double t_s) const {
  if (legs_.empty() || !(t_s >= 0.0)) return -1;
  // The first start after t, minus one: the leg whose interval holds t.
  const auto after = std::upper_bound(starts_s_.begin(), starts_s_.end(), t_s);
  return static_cast<int>(after - starts_s_.begin()) - 1;
}

Vec2 MissionPlan::velocityAt(double t_s) const {
  const int leg = legAt(t_s);
  if (leg < 0 || leg >= static_cast<int>(legs_.size())) return Vec2::Zero();
  return legs_[static_cast<std::size_t>(leg)].velocity_mps;
}

Vec2 MissionPlan::pathAt(double t_s) const {
  const int leg = legAt(t_s);
  if (leg < 0) return Vec2::Zero();
  if (leg >= static_cast<int>(legs_.size())) return points_.back();
  const auto i = static_cast<std::size_t>(leg);
  return points_[i] + legs_[i].velocity_mps * (t_s - starts_s_[i]);
}

}  // namespace swa::agent
