#pragma once
// A swarm mission (issue #45): a plan of legs that every agent holds alike, from its configuration or from the ground,
// never from another agent. The plan is a velocity over time in the stable frame (east, north), starting at one
// instant, ending in a hold; its path is the integral of that velocity from where the swarm was at the start.
//
// Legs are kept as velocity-over-time only: a leg "to a point at a speed" is turned into one when the plan is built
// (appendLegTo), from the end of the plan so far, so that the path runs through every point it names exactly. The
// velocity steps from leg to leg; a vehicle's own velocity loop smooths the step, and a first-order loop (the
// simulator's, DESIGN §4) ends where the plan ends once the hold has settled, its lag behind the path at the start of
// a leg being given back at its end.

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "swa/agent/geometry.h"

namespace swa::agent {

struct MissionLeg {
  Vec2 velocity_mps = Vec2::Zero();  // stable frame: x east, y north
  double duration_s = 0.0;
};

enum class MissionStart { kGnssLoss, kTime };
inline constexpr std::pair<MissionStart, const char*> kMissionStartNames[] = {{MissionStart::kGnssLoss, "gnss_loss"},
                                                                              {MissionStart::kTime, "time"}};

struct MissionConfig {
  std::vector<MissionLeg> legs;  // empty: no mission, the swarm holds where it is
  // When the first leg begins: the first GNSS sample that reports no fix, or the IMU stamp start_s (s on the IMU's
  // clock: the simulator's time, an autopilot's time since boot).
  MissionStart start = MissionStart::kGnssLoss;
  double start_s = 0.0;
  // The vehicle's velocity response: the time constant of a first-order step response (the simulator's
  // dynamics.velocity_lag_s, from which a scenario derives it). The swarm's frame follows the plan through it, so
  // that a leg's change of velocity, which the whole swarm flies together, is not taken for a UAV falling behind its
  // neighbours (and caught up twice: by the vehicle and by the formation law).
  double response_s = 1.0;
  // The fastest leg accepted: above it a plan is refused before take-off (a vehicle's cruise limit; PX4's
  // MPC_XY_VEL_MAX defaults to 12 m/s, the issue asks for up to 5).
  double max_speed_mps = 5.0;
};

// Appends the leg from the end of `legs` to `to_m` (relative to the plan's start) at `speed_mps`. A point the plan is
// already at adds nothing. False (nothing appended) when the speed is not positive and finite or the point is not
// finite.
bool appendLegTo(std::vector<MissionLeg>& legs, const Vec2& to_m, double speed_mps);

// A mission sent from the ground while the swarm flies (swa/swarm/mission): legs as the operator wrote them, resolved
// where the plan is when an agent receives the command, or a hold there. A plain group velocity is one velocity leg:
// it ends, and the swarm holds, when its time is up, so a ground link lost mid-command never sends the swarm away.
struct MissionCommandLeg {
  enum class Kind { kVelocity, kTo };
  Kind kind = Kind::kVelocity;
  Vec2 value = Vec2::Zero();  // kVelocity: m/s (east, north); kTo: the point in m, in the mission's frame
  double duration_s = 0.0;    // kVelocity
  double speed_mps = 0.0;     // kTo
};
struct MissionCommand {
  bool hold = false;  // stop where the plan has got to and hold there; `legs` empty
  std::vector<MissionCommandLeg> legs;
};

// Why `command` cannot be flown, or nothing: legs with a hold or neither, a non-finite value, a duration or speed not
// positive, a leg faster than `max_speed_mps`, a point farther than `max_abs_position_m` from the mission's start,
// more than kMaxMissionLegs legs.
std::optional<std::string> missionCommandProblem(const MissionCommand& command, double max_speed_mps,
                                                 double max_abs_position_m);

// Why `config` cannot be flown, or nothing: a non-finite or negative value, a leg faster than max_speed_mps, a
// zero-length leg, more than kMaxMissionLegs legs.
inline constexpr std::size_t kMaxMissionLegs = 1000;
std::optional<std::string> missionProblem(const MissionConfig& config);

class MissionPlan {
 public:
  MissionPlan() = default;
  explicit MissionPlan(std::vector<MissionLeg> legs);

  bool empty() const { return legs_.empty(); }
  std::size_t legCount() const { return legs_.size(); }
  double duration_s() const { return starts_s_.empty() ? 0.0 : starts_s_.back(); }
  // The leg in force `t_s` after the start: -1 before it, legCount() in the hold after the last.
  int legAt(double t_s) const;
  // The plan's velocity and path `t_s` after the start (zero before it; the end point and zero velocity after).
  Vec2 velocityAt(double t_s) const;
  Vec2 pathAt(double t_s) const;
  Vec2 endPoint() const { return points_.empty() ? Vec2::Zero() : points_.back(); }
  // The path's corners: the start (0, 0), then the end of every leg.
  const std::vector<Vec2>& waypoints() const { return points_; }
  const std::vector<MissionLeg>& legs() const { return legs_; }

 private:
  std::vector<MissionLeg> legs_;
  std::vector<double> starts_s_;  // leg i runs over [starts_s_[i], starts_s_[i + 1]); one more than legs_
  std::vector<Vec2> points_;      // the path at each start; one more than legs_
};

// The legs of `plan` flown `at_s` after its start: every leg begun by then, the one in force cut at at_s, and a hold
// up to at_s when the plan had ended. Followed by a command's legs (appendCommand), the plan replaced at at_s: the same
// path until then, and from the point it had reached, the command's.
std::vector<MissionLeg> flownUntil(const MissionPlan& plan, double at_s);
// Appends `command`'s legs (missionCommandProblem found nothing) to `legs`, its points resolved from their end.
void appendCommand(std::vector<MissionLeg>& legs, const MissionCommand& command);

}  // namespace swa::agent
