#include "swa/run_record/verdict.h"

#include <algorithm>
#include <cmath>

#include "swa/monitor/svg_plot.h"

namespace swa::record {
namespace {

std::string fixed(double v, int decimals) { return monitor::formatFixed(v, decimals); }

// The band of the final d_NB after a mission (issue #45): the swarm holds again, as tight as a hover is held.
constexpr double kMissionEndTolerance = 0.03;

}  // namespace

Verdict judge(const VerdictInput& in) {
  Verdict v;
  const monitor::Summary& s = in.summary;
  if (!in.saw_truth) {
    v.outcome = Outcome::kIncomplete;
    v.reasons.push_back("no ground truth received");
    if (!in.completed && !in.end_reason.empty()) v.reasons.push_back("run ended: " + in.end_reason);
    return v;
  }
  if (!in.completed) {
    v.reasons.push_back("scenario not completed: " + (in.end_reason.empty() ? "no end event" : in.end_reason));
  }

  const double r = in.scoring.formation.radius_m;
  // A mission (issue #45) is judged tighter at the end, when the swarm holds again, and by its d_NB while moving.
  const bool mission = !in.scoring.mission_legs.empty();
  const double tolerance =
      mission ? std::min(in.scoring.radius_tolerance, kMissionEndTolerance) : in.scoring.radius_tolerance;
  if (mission) {
    const double moving = s.mission_d_nb_moving_m;
    const double band = in.scoring.radius_tolerance;
    if (!std::isfinite(moving)) {
      v.reasons.push_back("the mission was not flown (it never started, or no two UAVs flew it)");
    } else if (std::fabs(moving - r) > band * r) {
      v.reasons.push_back("d_NB while moving " + fixed(moving, 3) + " m outside r = " + fixed(r, 3) + " m ± " +
                          fixed(100.0 * band, 1) + " %");
    }
  }
  const double d = s.mean_neighbor_distance_m;
  if (!std::isfinite(d)) {
    v.reasons.push_back("final d_NB undefined (fewer than 2 UAVs)");
  } else if (std::fabs(d - r) > tolerance * r) {
    v.reasons.push_back("final d_NB " + fixed(d, 3) + " m outside r = " + fixed(r, 3) + " m ± " +
                        fixed(100.0 * tolerance, 1) + " % [" + fixed(r * (1.0 - tolerance), 3) + ", " +
                        fixed(r * (1.0 + tolerance), 3) + "] m");
  }
  if (s.collisions > 0) v.reasons.push_back(std::to_string(s.collisions) + " collision(s)");
  if (s.groups != 1) v.reasons.push_back(std::to_string(s.groups) + " groups at the end (expected 1)");
  if (!in.failsafe_at_end.empty()) {
    std::string uavs;
    for (const int id : in.failsafe_at_end) uavs += (uavs.empty() ? "" : ", ") + std::to_string(id);
    v.reasons.push_back(std::string(in.failsafe_at_end.size() == 1 ? "UAV " : "UAVs ") + uavs +
                        " on failsafe at the end (agent declared dead, never rejoined)");
  }
  for (const ControlLoss& c : in.out_of_control_at_end) {
    v.reasons.push_back("UAV " + std::to_string(c.uav) + " out of SWA's control since " + fixed(c.t_s, 1) +
                        " s: " + c.text);
  }

  if (!in.missed.empty()) {
    double total = 0.0;
    std::string spans;
    for (std::size_t i = 0; i < in.missed.size(); ++i) {
      total += in.missed[i].to_s - in.missed[i].from_s;
      if (i < 3) spans += (i ? ", " : "") + fixed(in.missed[i].from_s, 1) + "-" + fixed(in.missed[i].to_s, 1) + " s";
    }
    if (in.missed.size() > 3) spans += ", ...";
    v.reasons.push_back("the monitor missed " + fixed(total, 1) + " s of the run (" + spans + ")");
  }

  if (!in.completed || !in.missed.empty()) {
    v.outcome = Outcome::kIncomplete;
  } else {
    v.outcome = v.reasons.empty() ? Outcome::kPass : Outcome::kFail;
  }
  if (v.outcome == Outcome::kFail && !in.failure_hint.empty()) v.reasons.push_back("likely because " + in.failure_hint);
  return v;
}

const char* toString(Outcome outcome) {
  switch (outcome) {
    case Outcome::kPass:
      return "PASS";
    case Outcome::kFail:
      return "FAIL";
    case Outcome::kIncomplete:
      return "INCOMPLETE";
  }
  return "INCOMPLETE";
}

std::optional<Outcome> parseOutcome(const std::string& text) {
  for (const Outcome o : {Outcome::kPass, Outcome::kFail, Outcome::kIncomplete}) {
    if (text == toString(o)) return o;
  }
  return std::nullopt;
}

int exitCode(Outcome outcome) {
  switch (outcome) {
    case Outcome::kPass:
      return 0;
    case Outcome::kFail:
      return 1;
    case Outcome::kIncomplete:
      return 3;
  }
  return 3;
}

std::string verdictText(const Verdict& verdict) {
  std::string out = toString(verdict.outcome);
  for (std::size_t k = 0; k < verdict.reasons.size(); ++k) out += (k == 0 ? ": " : "; ") + verdict.reasons[k];
  return out;
}

}  // namespace swa::record
