#pragma once
// A swarm's mission scored against its plan (issue #45): where the swarm went against where the plan said, from the
// truth. The plan's path starts at the swarm's centroid when the mission starts (every agent's plan starts where its
// swarm is), and each UAV's own path at that UAV's position then: a standalone UAV flies the plan on its own dead
// reckoning, and its own end error is what the swarm's centroid error is compared with.

#include <map>
#include <vector>

#include "swa/agent/mission.h"
#include "swa/monitor/swarm_metrics.h"

namespace swa::monitor {

struct MissionFigures {
  double end_error_m = kNaN;       // |centroid at the last step - (centroid at the start + the plan's end point)|
  double path_error_m = kNaN;      // mean over the plan's steps of |centroid - planned path|
  double d_nb_moving_m = kNaN;     // mean d_NB over the steps while the plan moves
  double uav_end_error_m = kNaN;   // mean over UAVs of |p_i(end) - (p_i(start) + the plan's end point)|
  double uav_end_spread_m = kNaN;  // the spread of the UAVs' end points: the std of their distance to their mean
};

// A plan changed live at `at_s` (the steps' clock) by a command from the ground, as every agent changes its own
// (agent/mission.h): the legs flown until then and the command's after, from `start_s`. A command before the plan has
// begun, or without one, starts the mission at at_s with the command's legs alone.
struct ReplannedMission {
  std::vector<agent::MissionLeg> legs;
  double start_s = 0.0;
};
ReplannedMission replanMission(const std::vector<agent::MissionLeg>& legs, double start_s, double at_s,
                               const agent::MissionCommand& command);

class MissionScore {
 public:
  MissionScore() = default;
  // `start_s`: when the plan's first leg begins, on the steps' clock.
  MissionScore(const agent::MissionPlan& plan, double start_s);

  bool active() const { return !plan_.empty(); }
  // The plan replaced by one with the same path until now (replanMission): what was scored stays.
  void replan(const agent::MissionPlan& plan, double start_s);
  void add(double t_s, const Geometry& geometry, const std::map<int, agent::Vec2>& positions);
  // The figures once the run is over: `positions` at its last step. NaN where the run never reached the start.
  MissionFigures figures(const Geometry& last, const std::map<int, agent::Vec2>& positions) const;

 private:
  agent::MissionPlan plan_;
  double start_s_ = kNaN;
  bool started_ = false;
  agent::Vec2 start_centroid_ = agent::Vec2::Zero();
  std::map<int, agent::Vec2> start_positions_;
  double path_error_sum_ = 0.0;
  double d_nb_sum_ = 0.0;
  int moving_steps_ = 0;
  int d_nb_steps_ = 0;
};

}  // namespace swa::monitor
